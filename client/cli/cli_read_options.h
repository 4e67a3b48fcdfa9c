/* cli_read_options.h — the reader options of every command that reads particle
 * files (snapshot, render, stream, view): --dataset and --step for HDF5 files and
 * --select for any, kept in an fc_read_options for fc_read_particles_with. */
#ifndef FC_CLI_READ_OPTIONS_H
#define FC_CLI_READ_OPTIONS_H

#include <stdbool.h>
#include <stdio.h>

#include "fluidcast_types.h"
#include "particle_reader.h"

/* Applies reader option `name` with its value to *o. FC_ERR_USAGE naming the
 * option for a bad value (the value string must outlive *o). */
fc_code fc_cli_set_read_option(fc_read_options *o, const char *name, const char *value, fc_error *err);

/* After the first file: says once, on stdout, that float64 positions far from the origin
 * were recentred and by what (nothing when they were not). */
void fc_cli_print_recentring(const fc_recentring *r);

/* A point given in the file's coordinates (--eye, --target) moved into the recentred frame. */
void fc_cli_recentre_point(const fc_recentring *r, float point[3]);

/* The "particle files" section of a command's help. step_is_stride: the
 * command's own --step is a sequence's frame stride (render, mesh), so the
 * readers' --step (an H5Part file's Step#N group) is not among its options. */
void fc_cli_print_read_options_help(FILE *to, bool step_is_stride);

#endif
