/* stream.h — `fluidcast stream`: push a sequence of particle files as frames. */
#ifndef FC_STREAM_H
#define FC_STREAM_H

/* Runs the subcommand on the arguments after "stream"; returns the exit status. */
int fc_stream_main(int argc, char **argv);

#endif
