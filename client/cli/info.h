/* info.h — `fluidcast info`: what a server is and what it is doing. */
#ifndef FC_INFO_H
#define FC_INFO_H

/* Runs the subcommand on the arguments after "info"; returns the exit status. */
int fc_info_main(int argc, char **argv);

#endif
