/* mesh_command.h — `fluidcast mesh`: particle files to surface mesh files,
 * extracted by the server (PROTOCOL.md section 13), one file per frame. */
#ifndef FC_MESH_COMMAND_H
#define FC_MESH_COMMAND_H

/* Runs the subcommand on the arguments after "mesh"; returns the exit status (cli_report.h). */
int fc_mesh_main(int argc, char **argv);

#endif
