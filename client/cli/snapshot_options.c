/* snapshot_options.c — see snapshot_options.h. */
#include "snapshot_options.h"

#include <string.h>

#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "output_file.h"

typedef fc_code (*option_handler)(fc_snapshot_options *o, const char *name, const char *value,
                                  fc_error *err);

static fc_code set_output(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    (void)err;
    o->output = value;
    return FC_OK;
}

static fc_code set_server(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    (void)err;
    o->server = value;
    return FC_OK;
}

static fc_code set_size(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_size(name, value, &o->width, &o->height, err);
}

static fc_code set_eye(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    o->has_eye = true;
    return fc_cli_parse_vec3(name, value, o->eye, err);
}

static fc_code set_target(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    o->has_target = true;
    return fc_cli_parse_vec3(name, value, o->target, err);
}

static fc_code set_up(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    o->has_up = true;
    return fc_cli_parse_vec3(name, value, o->up, err);
}

static fc_code set_fov(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    o->has_fov = true;
    fc_code code = fc_cli_parse_float(name, value, &o->fov_deg, err);
    if (code == FC_OK && !(o->fov_deg > 0.0f && o->fov_deg < 180.0f))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs degrees between 0 and 180, not %s", name, value);
    return code;
}

static fc_code set_radius(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    fc_code code = fc_cli_parse_float(name, value, &o->radius, err);
    if (code == FC_OK && !(o->radius > 0.0f))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a positive radius, not %s", name, value);
    return code;
}

static fc_code set_smoothing(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    static const char *const names[] = { "none", "curvature", NULL };
    static const fc_smoothing values[] = { FC_SMOOTHING_NONE, FC_SMOOTHING_CURVATURE };
    int index;
    fc_code code = fc_cli_parse_choice(name, value, names, &index, err);
    if (code == FC_OK) {
        o->has_smoothing = true;
        o->smoothing = values[index];
    }
    return code;
}

static fc_code set_iterations(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    o->has_iterations = true;
    return fc_cli_parse_uint(name, value, 0, 1000, &o->iterations, err);
}

static fc_code set_aov(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    static const char *const names[] = { "depth", "smoothed-depth", "thickness", NULL };
    static const fc_aov values[] = { FC_AOV_DEPTH, FC_AOV_SMOOTHED_DEPTH, FC_AOV_THICKNESS };
    int index;
    fc_code code = fc_cli_parse_choice(name, value, names, &index, err);
    if (code == FC_OK)
        o->aov = values[index];
    return code;
}

static fc_code set_quality(fc_snapshot_options *o, const char *name, const char *value, fc_error *err)
{
    o->has_quality = true;
    return fc_cli_parse_uint(name, value, 1, 100, &o->quality, err);
}

typedef struct option_spec {
    const char *name;
    option_handler handle;
} option_spec;

static const option_spec options[] = {
    { "-o", set_output },          { "--output", set_output },   { "--server", set_server },
    { "--size", set_size },        { "--eye", set_eye },         { "--target", set_target },
    { "--up", set_up },            { "--fov", set_fov },         { "--radius", set_radius },
    { "--smoothing", set_smoothing }, { "--iterations", set_iterations }, { "--aov", set_aov },
    { "--quality", set_quality },
};

/* Finds the option `arg` names, as "--name" or "--name=value" (then *inline_value
 * points at the value). NULL when unknown. */
static const option_spec *find_option(const char *arg, const char **inline_value)
{
    *inline_value = NULL;
    size_t name_len = strcspn(arg, "=");
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++) {
        if (strlen(options[i].name) == name_len && strncmp(arg, options[i].name, name_len) == 0) {
            if (arg[name_len] == '=')
                *inline_value = arg + name_len + 1;
            return &options[i];
        }
    }
    return NULL;
}

static void set_defaults(fc_snapshot_options *o)
{
    memset(o, 0, sizeof *o);
    o->server = FC_SNAPSHOT_DEFAULT_SERVER;
    o->width = 1280;
    o->height = 720;
    o->up[2] = 1.0f;
    o->fov_deg = FC_SNAPSHOT_DEFAULT_FOV;
    o->aov = FC_AOV_COLOR;
    o->quality = FC_SNAPSHOT_DEFAULT_QUALITY;
}

/* An explicit camera is checked before any file is read, so a mistyped vector
 * is a usage error rather than a server rejection after the upload. */
static fc_code check_explicit_camera(const fc_snapshot_options *o, fc_error *err)
{
    if (o->has_eye != o->has_target)
        return fc_error_set(err, FC_ERR_USAGE, "--eye and --target go together: give both or neither");
    if (!o->has_eye)
        return FC_OK;
    fc_camera cam;
    memcpy(cam.eye, o->eye, sizeof cam.eye);
    memcpy(cam.target, o->target, sizeof cam.target);
    memcpy(cam.up, o->up, sizeof cam.up);
    cam.fov_y_deg = o->fov_deg;
    cam.width = o->width;
    cam.height = o->height;
    fc_error why;
    if (fc_camera_validate(&cam, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "bad camera: %s", why.message);
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
    if (o->aov != FC_AOV_COLOR && o->format != FC_FORMAT_EXR)
        return fc_error_set(err, FC_ERR_USAGE, "--aov writes one float channel: the output must be .exr");
    if (o->has_quality && o->format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--quality applies to .jpg/.jpeg output only");
    return check_explicit_camera(o, err);
}

fc_code fc_snapshot_parse(int argc, char **argv, fc_snapshot_options *out, fc_error *err)
{
    set_defaults(out);
    for (int i = 0; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            out->help = true;
            return FC_OK;
        }
        if (arg[0] != '-' || arg[1] == '\0') {
            if (out->input)
                return fc_error_set(err, FC_ERR_USAGE, "unexpected argument \"%s\" (one input file only)", arg);
            out->input = arg;
            continue;
        }
        const char *value;
        const option_spec *spec = find_option(arg, &value);
        if (!spec)
            return fc_error_set(err, FC_ERR_USAGE, "unknown option %s (see fluidcast snapshot --help)", arg);
        if (!value) {
            if (i + 1 >= argc)
                return fc_error_set(err, FC_ERR_USAGE, "%s needs a value", spec->name);
            value = argv[++i];
        }
        fc_code code = spec->handle(out, spec->name, value, err);
        if (code != FC_OK)
            return code;
    }
    return check_combinations(out, err);
}

void fc_snapshot_print_help(FILE *to)
{
    fputs("usage: fluidcast snapshot INPUT -o OUT [options]\n"
          "\n"
          "Sends the particles in INPUT (.f32, .ply, .vtk, .csv) to a fluidcastd server,\n"
          "renders them as fluid and writes the image the server encoded to OUT. The\n"
          "format follows OUT's extension: .png, .jpg/.jpeg or .exr.\n"
          "\n"
          "options:\n"
          "  -o, --output OUT        image file to write (required)\n"
          "  --server HOST:PORT      server address (default " FC_SNAPSHOT_DEFAULT_SERVER ";\n"
          "                          port 7450 when omitted; IPv6 as [::1]:7450)\n"
          "  --size WxH              image size in pixels (default 1280x720)\n"
          "  --eye X,Y,Z             camera position; needs --target\n"
          "  --target X,Y,Z          point the camera looks at; needs --eye\n"
          "                          (without both, the camera frames the particles'\n"
          "                          bounding box)\n"
          "  --up X,Y,Z              camera up direction (default 0,0,1)\n"
          "  --fov DEG               vertical field of view in degrees (default 40)\n"
          "  --radius R              particle sphere radius in world units; without it\n"
          "                          the radius is estimated from the particle spacing\n"
          "                          (0.9 x the median nearest-neighbour distance) and\n"
          "                          the radius used is printed\n"
          "  --smoothing MODE        curvature (default) or none\n"
          "  --iterations N          smoothing iterations, 0..1000 (default 40)\n"
          "  --aov NAME              write an arbitrary output variable instead of the\n"
          "                          colour: depth, smoothed-depth (linear distance along\n"
          "                          the view axis, 0 where there is no fluid) or\n"
          "                          thickness; one float32 channel, needs .exr\n"
          "  --quality Q             JPEG quality 1..100 (default 90; .jpg/.jpeg only)\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}
