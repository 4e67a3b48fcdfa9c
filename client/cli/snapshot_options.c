/* snapshot_options.c — see snapshot_options.h. */
#include "snapshot_options.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_setting_options.h"
#include "cli_values.h"
#include "fc_colormap.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fc_options.h"
#include "output_file.h"

static fc_code set_output(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    (void)name;
    (void)err;
    o->output = value;
    return FC_OK;
}

static fc_code set_server(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    (void)name;
    (void)err;
    o->server = value;
    return FC_OK;
}

static fc_code set_size(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    return fc_cli_parse_size(name, value, &o->width, &o->height, err);
}

static fc_code set_eye(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    o->has_eye = true;
    return fc_cli_parse_vec3(name, value, o->eye, err);
}

static fc_code set_target(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    o->has_target = true;
    return fc_cli_parse_vec3(name, value, o->target, err);
}

static fc_code set_up(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    o->has_up = true;
    return fc_cli_parse_up(name, value, o->up, err);
}

static fc_code set_fov(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    o->has_fov = true;
    fc_code code = fc_cli_parse_float(name, value, &o->fov_deg, err);
    if (code == FC_OK && !(o->fov_deg > 0.0f && o->fov_deg < 180.0f))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs degrees between 0 and 180, not %s", name, value);
    return code;
}

static fc_code set_aov(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    static const char *const names[] = {"depth", "smoothed-depth", "thickness", "normal", "noise", NULL};
    static const fc_aov values[] = {FC_AOV_DEPTH, FC_AOV_SMOOTHED_DEPTH, FC_AOV_THICKNESS, FC_AOV_NORMAL,
                                    FC_AOV_NOISE};
    int index;
    fc_code code = fc_cli_parse_choice(name, value, names, &index, err);
    if (code == FC_OK)
        o->aov = values[index];
    return code;
}

static fc_code set_quality(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    o->has_quality = true;
    return fc_cli_parse_uint(name, value, 1, 100, &o->quality, err);
}

/* ---- scene images: the files are checked once the command line is complete ---- */

static fc_code set_background(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    if (value[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs an image file", name);
    o->background = value;
    return FC_OK;
}

static fc_code set_cubemap(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    if (value[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs six image files or a directory", name);
    o->cubemap = value;
    return FC_OK;
}

static fc_code set_mesh(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    if (o->mesh_count == FC_CLI_MAX_MESHES)
        return fc_error_set(err, FC_ERR_USAGE, "%s: at most %d meshes", name, FC_CLI_MAX_MESHES);
    fc_code code = fc_cli_mesh_parse(value, &o->meshes[o->mesh_count], err);
    if (code == FC_OK)
        o->mesh_count++;
    return code;
}

static fc_code set_read(void *target, const char *name, const char *value, fc_error *err)
{
    fc_snapshot_options *o = target;
    return fc_cli_set_read_option(&o->read, name, value, err);
}

/* snapshot's own options (their help is written below); the render settings'
 * come from the settings table (fc_cli_take_setting). */
static const fc_option options[] = {
    {"-o", "OUT", set_output, NULL, NULL},
    {"--output", "OUT", set_output, NULL, NULL},
    {"--server", "HOST:PORT", set_server, NULL, NULL},
    {"--size", "WxH", set_size, NULL, NULL},
    {"--eye", "X,Y,Z", set_eye, NULL, NULL},
    {"--target", "X,Y,Z", set_target, NULL, NULL},
    {"--up", "UP", set_up, NULL, NULL},
    {"--fov", "DEG", set_fov, NULL, NULL},
    {"--background", "IMAGE", set_background, NULL, NULL},
    {"--cubemap", "FILES", set_cubemap, NULL, NULL},
    {"--mesh", "FILE", set_mesh, NULL, NULL},
    {"--aov", "NAME", set_aov, NULL, NULL},
    {"--quality", "Q", set_quality, NULL, NULL},
    {"--dataset", "PATH", set_read, NULL, NULL},
    {"--step", "N", set_read, NULL, NULL},
    {"--select", "SELECTION", set_read, NULL, NULL},
};

static const fc_option_table own_table = {"fluidcast snapshot", options, sizeof options / sizeof options[0], NULL,
                                          NULL};

void fc_snapshot_set_defaults(fc_snapshot_options *o)
{
    memset(o, 0, sizeof *o);
    o->read.recentring = &o->recentring;
    o->server = FC_DEFAULT_SERVER;
    o->width = 1280;
    o->height = 720;
    o->fov_deg = FC_SNAPSHOT_DEFAULT_FOV;
    fc_cli_settings_init(&o->settings);
    o->aov = FC_AOV_COLOR;
    o->quality = FC_SNAPSHOT_DEFAULT_QUALITY;
}

/* Without --up the up direction is only known once the particles are read:
 * until then a unit axis across the view stands in, so that eye, target, fov
 * and size are checked now. */
static void stand_in_up(const fc_snapshot_options *o, float up[3])
{
    int across = 0;
    for (int k = 1; k < 3; k++)
        if (fabsf(o->target[k] - o->eye[k]) < fabsf(o->target[across] - o->eye[across]))
            across = k;
    for (int k = 0; k < 3; k++)
        up[k] = k == across ? 1.0f : 0.0f;
}

/* An explicit camera is checked before any file is read, so a mistyped vector
 * is a usage error rather than a server rejection after the upload. */
fc_code fc_snapshot_check_camera(const fc_snapshot_options *o, fc_error *err)
{
    if (o->has_eye != o->has_target)
        return fc_error_set(err, FC_ERR_USAGE, "--eye and --target go together: give both or neither");
    if (!o->has_eye)
        return FC_OK;
    fc_camera cam;
    memcpy(cam.eye, o->eye, sizeof cam.eye);
    memcpy(cam.target, o->target, sizeof cam.target);
    if (o->has_up)
        memcpy(cam.up, o->up, sizeof cam.up);
    else
        stand_in_up(o, cam.up);
    cam.fov_y_deg = o->fov_deg;
    cam.width = o->width;
    cam.height = o->height;
    fc_error why;
    if (fc_camera_validate(&cam, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "bad camera: %s", why.message);
    return FC_OK;
}

fc_code fc_snapshot_check_coloring(const fc_snapshot_options *o, fc_error *err)
{
    if (o->settings.values.color_by != FC_COLOR_BY_NONE)
        return FC_OK;
    if (fc_cli_setting_given(&o->settings, "colormap"))
        return fc_error_set(err, FC_ERR_USAGE, "--colormap applies with --color-by speed|density");
    if (fc_cli_setting_given(&o->settings, "color_range"))
        return fc_error_set(err, FC_ERR_USAGE, "--range applies with --color-by speed|density");
    if (o->legend)
        return fc_error_set(err, FC_ERR_USAGE, "--legend applies with --color-by speed|density");
    return FC_OK;
}

static fc_code check_combinations(fc_snapshot_options *o, fc_error *err)
{
    if (!o->input)
        return fc_error_set(err, FC_ERR_USAGE, "snapshot needs an input particle file");
    if (!o->output)
        return fc_error_set(err, FC_ERR_USAGE, "snapshot needs an output image: -o OUT.png|.jpg|.exr");
    fc_code code = fc_output_format_from_path(o->output, &o->format, err);
    if (code != FC_OK)
        return code;
    if (o->legend && o->aov != FC_AOV_COLOR)
        return fc_error_set(err, FC_ERR_USAGE, "--legend goes on the colour image, not an --aov");
    if (o->aov != FC_AOV_COLOR && o->format != FC_FORMAT_EXR)
        return fc_error_set(err, FC_ERR_USAGE, "--aov writes float channels: the output must be .exr");
    if (o->has_quality && o->format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--quality applies to .jpg/.jpeg output only");
    if (fc_cli_setting_given(&o->settings, "jpeg_subsampling") && o->format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--jpeg-subsampling applies to .jpg/.jpeg output only");
    code = fc_snapshot_check_coloring(o, err);
    return code != FC_OK ? code : fc_snapshot_check_camera(o, err);
}

fc_code fc_snapshot_take_option(fc_snapshot_options *o, int argc, char **argv, int *i, bool *known, fc_error *err)
{
    fc_code code = fc_options_take(&own_table, argc, argv, i, o, known, err);
    if (*known)
        return code;
    return fc_cli_take_setting(&o->settings, argc, argv, i, known, err);
}

fc_code fc_snapshot_parse(int argc, char **argv, fc_snapshot_options *out, fc_error *err)
{
    fc_snapshot_set_defaults(out);
    for (int i = 0; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            out->help = true;
            return FC_OK;
        }
        /* snapshot's own flag, outside the table the render command shares. */
        if (strcmp(arg, "--legend") == 0) {
            out->legend = true;
            continue;
        }
        if (arg[0] != '-' || arg[1] == '\0') {
            if (out->input)
                return fc_error_set(err, FC_ERR_USAGE, "unexpected argument \"%s\" (one input file only)", arg);
            out->input = arg;
            continue;
        }
        bool known;
        fc_code code = fc_snapshot_take_option(out, argc, argv, &i, &known, err);
        if (!known)
            return fc_error_set(err, FC_ERR_USAGE, "unknown option %s (see fluidcast snapshot --help)", arg);
        if (code != FC_OK)
            return code;
    }
    return check_combinations(out, err);
}

static void print_camera_help(FILE *to)
{
    fputs("camera and image:\n"
          "  -o, --output OUT        image file to write (required)\n"
          "  --server HOST:PORT      server address (default " FC_DEFAULT_SERVER ";\n"
          "                          port 7450 when omitted; IPv6 as [::1]:7450)\n"
          "                          or srv:NAME: one daemon of a DNS SRV name\n"
          "  --size WxH              image size in pixels (default 1280x720)\n"
          "  --eye X,Y,Z             camera position; needs --target\n"
          "  --target X,Y,Z          point the camera looks at; needs --eye\n"
          "                          (without both, the camera frames the fluid: the\n"
          "                          particles' bounding box without droplets flung far\n"
          "                          from the rest, which a line then counts)\n"
          "  --up X,Y,Z|x|y|z|-x|-y|-z\n"
          "                          world direction shown as up in the picture (the\n"
          "                          letters are the unit axes); default: guessed from\n"
          "                          the particles as the axis whose one end is a flat,\n"
          "                          dense floor and the other a free surface thinning\n"
          "                          out, +z when none stands out; the guess is printed.\n"
          "                          Without --eye the camera frames the particles from\n"
          "                          above, above meaning along this up direction\n"
          "  --fov DEG               vertical field of view in degrees (default 40)\n"
          "  --aov NAME              write an arbitrary output variable instead of the\n"
          "                          colour, as float channels; needs .exr:\n"
          "                          depth, smoothed-depth (linear distance along the\n"
          "                          view axis, 0 where there is no fluid), thickness,\n"
          "                          normal (view-space surface normal, RGB) or noise\n"
          "  --quality Q             JPEG quality 1..100 (default 90; .jpg/.jpeg only)\n"
          "  --legend                draw a colour bar with the attribute's name and five\n"
          "                          tick labels into the image's top-right corner (with\n"
          "                          --color-by; drawn by the client with FreeType)\n"
          "\n",
          to);
}

void fc_snapshot_print_settings_help(FILE *to)
{
    fc_settings defaults;
    fc_settings_default(&defaults);
    fc_cli_print_settings_help(to, &defaults);
}

void fc_snapshot_print_help(FILE *to)
{
    fputs("usage: fluidcast snapshot INPUT -o OUT [options]\n"
          "\n"
          "Sends the particles in INPUT (.f32, .ply, .vtk, .vtu, .vtp, .pvd, .csv, .npy,\n.bgeo, HDF5) to a fluidcastd server,\n"
          "renders them as fluid and writes the image the server encoded to OUT. The\n"
          "format follows OUT's extension: .png, .jpg/.jpeg or .exr. Options take their\n"
          "value as the next argument or after '=' (--ior=1.5).\n"
          "\n",
          to);
    print_camera_help(to);
    fc_cli_print_read_options_help(to, false);
    fc_snapshot_print_settings_help(to);
    fputs("  -h, --help              show this help\n\n", to);
    fc_cli_print_exit_codes(to);
}
