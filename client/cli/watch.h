/* watch.h — `fluidcast watch`: follow a session's frames as a viewer. */
#ifndef FC_WATCH_H
#define FC_WATCH_H

/* Runs the subcommand on the arguments after "watch"; returns the exit status. */
int fc_watch_main(int argc, char **argv);

#endif
