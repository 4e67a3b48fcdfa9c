/* cli_particles.h — reading one particle file for a subcommand, with the
 * failure told the CLI's way (exit status FC_EXIT_INPUT). */
#ifndef FC_CLI_PARTICLES_H
#define FC_CLI_PARTICLES_H

#include "fluidcast_types.h"
#include "particle_reader.h"

/* Reads (with the command's reader options, NULL: defaults) and validates the file
 * into *frame (free it with fc_frame_free even on failure). Returns FC_EXIT_OK or
 * FC_EXIT_INPUT after printing why. */
int fc_cli_load_particles(const char *path, const fc_read_options *options, fc_frame *frame);

#endif
