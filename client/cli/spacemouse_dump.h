/* spacemouse_dump.h — `fluidcast spacemouse --dump`: a SpaceMouse's raw and
 * decoded reports, for checking a real device (and for the umockdev tests). */
#ifndef FC_SPACEMOUSE_DUMP_H
#define FC_SPACEMOUSE_DUMP_H

/* Runs the subcommand on the arguments after "spacemouse"; returns the exit status. */
int fc_spacemouse_main(int argc, char **argv);

#endif
