/* view_options.h — the command line of `fluidcast view` and its help, which
 * lists the mouse, key and SpaceMouse bindings. */
#ifndef FC_VIEW_OPTIONS_H
#define FC_VIEW_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "cli_setting_options.h"
#include "fluidcast_types.h"
#include "particle_reader.h"

#define FC_VIEW_MAX_FILES 100000

typedef struct fc_view_options {
    bool help;
    const char *server;
    const char *session;          /* follow this session; NULL: play files */
    const char **files;           /* the sequence, in order (owned: free with fc_view_options_free) */
    uint32_t file_count;
    uint32_t width, height;       /* initial window size */
    fc_image_format format;       /* how images travel: RAW (default), JPEG or H264 */
    fc_cli_settings settings;     /* the render settings' options; JPEG chroma 4:2:0 unless given */
    float fps;                    /* playback rate of a sequence */
    bool no_spacemouse;
    bool log_camera;              /* print every camera sent to the daemon (tests, debugging) */
    const char *test_script;      /* test hook: see view_script.h */
    fc_read_options read;         /* --dataset, --step, --select (cli_read_options.h) */
    fc_recentring recentring;     /* read.recentring points here */
} fc_view_options;

fc_code fc_view_parse(int argc, char **argv, fc_view_options *o, fc_error *err);
void fc_view_options_free(fc_view_options *o);
void fc_view_print_help(FILE *to);

#endif
