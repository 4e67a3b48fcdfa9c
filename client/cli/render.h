/* render.h — `fluidcast render`: a sequence of particle files rendered, in
 * order, to a video or to numbered images, with one camera for the whole
 * sequence. */
#ifndef FC_RENDER_H
#define FC_RENDER_H

/* Runs the subcommand on the arguments after "render"; returns the exit status
 * (cli_report.h). */
int fc_render_main(int argc, char **argv);

#endif
