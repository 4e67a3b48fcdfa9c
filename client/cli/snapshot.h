/* snapshot.h — `fluidcast snapshot`: one particle file in, one rendered image out. */
#ifndef FC_SNAPSHOT_H
#define FC_SNAPSHOT_H

/* Runs the subcommand on the arguments after "snapshot"; returns the exit status
 * (cli_report.h). */
int fc_snapshot_main(int argc, char **argv);

#endif
