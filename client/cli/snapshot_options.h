/* snapshot_options.h — the command line of `fluidcast snapshot`: parsing,
 * checking the combinations, and the help text. */
#ifndef FC_SNAPSHOT_OPTIONS_H
#define FC_SNAPSHOT_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "fluidcast_types.h"

#define FC_SNAPSHOT_DEFAULT_SERVER "127.0.0.1:7450"
#define FC_SNAPSHOT_DEFAULT_FOV 40.0f
#define FC_SNAPSHOT_DEFAULT_QUALITY 90u

typedef struct fc_snapshot_options {
    bool help;                     /* --help: print the help and do nothing else */
    const char *input;             /* particle file */
    const char *output;            /* image file; its extension chose `format` */
    fc_image_format format;
    const char *server;            /* HOST:PORT */
    uint32_t width, height;
    bool has_eye, has_target, has_up;
    float eye[3], target[3], up[3];   /* up only when has_up: otherwise it is guessed from the particles */
    bool has_fov;
    float fov_deg;
    fc_settings settings;          /* fc_settings_default plus the flags; radius 0: estimate from the spacing */
    const char *background;        /* --background IMAGE, or NULL */
    const char *cubemap;           /* --cubemap value (six files or a directory), or NULL */
    fc_aov aov;
    bool has_quality;
    bool has_iterations;      /* --iterations given: --smoothing keeps it */
    bool has_density_threshold;   /* --density-threshold given: no spray threshold from the frame's densities */
    uint32_t quality;
} fc_snapshot_options;

/* Parses the arguments after "snapshot". FC_ERR_USAGE with the reason (naming
 * the option) for an unknown option, a bad value, a render setting outside its
 * domain, a missing input/output, an unsupported output extension, --aov
 * without .exr, --quality without .jpg, or half a camera. */
fc_code fc_snapshot_parse(int argc, char **argv, fc_snapshot_options *out, fc_error *err);

void fc_snapshot_print_help(FILE *to);

#endif
