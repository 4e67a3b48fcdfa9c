/* mesh_options.h — the command line of `fluidcast mesh`: particle files (as
 * render takes them), the output file or %d pattern, which attributes to ask
 * for, and the render settings' options, of which the surface_* ones shape
 * the mesh (cli_setting_options.h). */
#ifndef FC_MESH_OPTIONS_H
#define FC_MESH_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "cli_setting_options.h"
#include "mesh_write.h"
#include "particle_reader.h"
#include "render_inputs.h"

typedef struct fc_mesh_options {
    bool help;
    const char *server;
    const char *output;            /* one file, or a pattern with one %d for a sequence */
    fc_mesh_file_format format;    /* from the output's extension */
    const char **inputs;           /* INPUTS as given (malloc'd array of argv pointers) */
    uint32_t input_count;
    fc_frame_range range;          /* --start/--end/--step */
    bool skip_existing;
    uint32_t attributes;           /* FC_SURFACE_* bits to ask for */
    fc_read_options read;
    fc_cli_settings settings;
} fc_mesh_options;

/* Parses the arguments after "mesh". FC_ERR_USAGE for an unknown option or
 * bad value, no input or no output, an output that is not .ply/.obj/.vtp/.stl,
 * --attributes for a format that has no place for them. Whether one output
 * file fits the inputs is known once they are expanded (fluidcast mesh checks
 * it). Free with fc_mesh_options_free. */
fc_code fc_mesh_parse(int argc, char **argv, fc_mesh_options *out, fc_error *err);
void fc_mesh_options_free(fc_mesh_options *o);
void fc_mesh_print_help(FILE *to);

#endif
