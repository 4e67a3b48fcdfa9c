/* stream_options.h — the command line of `fluidcast stream`. */
#ifndef FC_STREAM_OPTIONS_H
#define FC_STREAM_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "cli_setting_options.h"
#include "fluidcast.h"
#include "particle_reader.h"

#define FC_STREAM_MAX_FILES 100000

typedef struct fc_stream_options {
    bool help;
    const char **files;            /* the particle files, in order (malloc'd array of argv pointers) */
    uint32_t file_count;
    const char *server;
    const char *session;           /* NULL: no named session */
    const char *out_dir;           /* NULL: no images requested */
    fc_image_format format;
    bool has_quality;
    uint32_t quality;
    uint32_t width, height;
    fc_cli_settings settings;      /* the render settings' options; radius 0: from the first frame */
    bool has_up;
    float up[3];                   /* only when has_up: otherwise guessed from the first frame */
    fc_upload_options upload;
    fc_read_options read;          /* --dataset, --step, --select (cli_read_options.h) */
    fc_recentring recentring;      /* read.recentring points here */
} fc_stream_options;

/* Parses the arguments after "stream". FC_ERR_USAGE for a bad option, no
 * files, or --quality without JPEG. Free with fc_stream_options_free. */
fc_code fc_stream_parse(int argc, char **argv, fc_stream_options *out, fc_error *err);
void fc_stream_options_free(fc_stream_options *o);
void fc_stream_print_help(FILE *to);

#endif
