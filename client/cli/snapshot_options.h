/* snapshot_options.h — the command line of `fluidcast snapshot`: parsing,
 * checking the combinations, and the help text. */
#ifndef FC_SNAPSHOT_OPTIONS_H
#define FC_SNAPSHOT_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "fluidcast_types.h"
#include "cli_mesh.h"
#include "cli_setting_options.h"
#include "particle_reader.h"

#include "fc_host_port.h"   /* FC_DEFAULT_SERVER */
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
    fc_cli_settings settings;      /* fc_settings_default plus the settings' options; radius 0: estimate */
    const char *background;        /* --background IMAGE, or NULL */
    const char *cubemap;           /* --cubemap value (six files or a directory), or NULL */
    fc_aov aov;
    bool has_quality;
    bool legend;                   /* --legend: a colour bar drawn into the image (snapshot_legend.h) */
    uint32_t quality;
    fc_read_options read;          /* --dataset, --step, --select (cli_read_options.h) */
    fc_recentring recentring;      /* read.recentring points here (fc_snapshot_set_defaults) */
    fc_cli_mesh meshes[FC_CLI_MAX_MESHES];   /* --mesh, in order: mesh i is sent as id i + 1 (cli_mesh.h) */
    int mesh_count;
} fc_snapshot_options;

/* Parses the arguments after "snapshot". FC_ERR_USAGE with the reason (naming
 * the option) for an unknown option, a bad value, a render setting outside its
 * domain, a missing input/output, an unsupported output extension, --aov
 * without .exr, --quality without .jpg, or half a camera. */
fc_code fc_snapshot_parse(int argc, char **argv, fc_snapshot_options *out, fc_error *err);

void fc_snapshot_print_help(FILE *to);

/* ---- the same options for other commands (`fluidcast render`) ---- */

/* The defaults fc_snapshot_parse starts from. */
void fc_snapshot_set_defaults(fc_snapshot_options *o);

/* When argv[*i] is one of snapshot's options (camera, image, render
 * settings, scene images), applies it with its value (consuming the next
 * argument when the value is not given after '=') and sets *known; leaves *o
 * alone and clears *known otherwise. FC_ERR_USAGE as fc_snapshot_parse. */
fc_code fc_snapshot_take_option(fc_snapshot_options *o, int argc, char **argv, int *i, bool *known,
                                fc_error *err);

/* Checks --eye/--target (both or neither) and the camera they make with
 * --up, --fov and --size, as fc_snapshot_parse does. */
fc_code fc_snapshot_check_camera(const fc_snapshot_options *o, fc_error *err);

/* --colormap and --range need --color-by: FC_ERR_USAGE naming the option otherwise. */
fc_code fc_snapshot_check_coloring(const fc_snapshot_options *o, fc_error *err);

/* The help of the render settings: the "fluid surface", "shading" and "colour by attribute" sections. */
void fc_snapshot_print_settings_help(FILE *to);

#endif
