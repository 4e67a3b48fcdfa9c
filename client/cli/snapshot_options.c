/* snapshot_options.c — see snapshot_options.h. */
#include "snapshot_options.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_colormap.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "output_file.h"

typedef struct option_spec option_spec;
typedef fc_code (*option_handler)(fc_snapshot_options *o, const option_spec *spec, const char *value,
                                  fc_error *err);

struct option_spec {
    const char *name;
    option_handler handle;
    size_t setting;   /* offset of the fc_settings field the generic setting handlers fill */
};

static fc_code set_output(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    (void)spec;
    (void)err;
    o->output = value;
    return FC_OK;
}

static fc_code set_server(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    (void)spec;
    (void)err;
    o->server = value;
    return FC_OK;
}

static fc_code set_size(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    return fc_cli_parse_size(spec->name, value, &o->width, &o->height, err);
}

static fc_code set_eye(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_eye = true;
    return fc_cli_parse_vec3(spec->name, value, o->eye, err);
}

static fc_code set_target(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_target = true;
    return fc_cli_parse_vec3(spec->name, value, o->target, err);
}

static fc_code set_up(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_up = true;
    return fc_cli_parse_up(spec->name, value, o->up, err);
}

static fc_code set_fov(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_fov = true;
    fc_code code = fc_cli_parse_float(spec->name, value, &o->fov_deg, err);
    if (code == FC_OK && !(o->fov_deg > 0.0f && o->fov_deg < 180.0f))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs degrees between 0 and 180, not %s", spec->name, value);
    return code;
}

/* ---- render settings: the domains are fc_settings_validate's, so the
 * command line accepts exactly what the server does ---- */

static fc_code check_settings(const fc_snapshot_options *o, const char *option, fc_error *err)
{
    fc_error why;
    if (fc_settings_validate(&o->settings, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "%s: %s", option, why.message);
    return FC_OK;
}

static void *setting_field(fc_snapshot_options *o, const option_spec *spec)
{
    return (char *)&o->settings + spec->setting;
}

static fc_code set_float_setting(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    fc_code code = fc_cli_parse_float(spec->name, value, setting_field(o, spec), err);
    return code != FC_OK ? code : check_settings(o, spec->name, err);
}

static fc_code set_uint_setting(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    fc_code code = fc_cli_parse_uint(spec->name, value, 0, UINT32_MAX, setting_field(o, spec), err);
    return code != FC_OK ? code : check_settings(o, spec->name, err);
}

static fc_code set_rgb_setting(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    fc_code code = fc_cli_parse_vec3(spec->name, value, setting_field(o, spec), err);
    return code != FC_OK ? code : check_settings(o, spec->name, err);
}

/* 0 would mean "estimate" on the wire; on the command line that is leaving the option out. */
static fc_code set_radius(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    fc_code code = fc_cli_parse_float(spec->name, value, &o->settings.radius, err);
    if (code == FC_OK && !(o->settings.radius > 0.0f))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a positive radius, not %s", spec->name, value);
    return code != FC_OK ? code : check_settings(o, spec->name, err);
}

static fc_code set_smoothing(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    static const char *const names[] = {"none", "curvature", "bilateral", "binomial", "narrow", NULL};
    static const fc_smoothing values[] = {FC_SMOOTHING_NONE, FC_SMOOTHING_CURVATURE, FC_SMOOTHING_BILATERAL,
                                          FC_SMOOTHING_BINOMIAL, FC_SMOOTHING_NARROW};
    int index;
    fc_code code = fc_cli_parse_choice(spec->name, value, names, &index, err);
    if (code == FC_OK) {
        o->settings.smoothing = values[index];
        if (!o->has_iterations)
            o->settings.iterations = fc_smoothing_default_iterations(values[index]);
    }
    return code;
}

static fc_code set_kernel(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    static const char *const names[] = {"sphere", "anisotropic", NULL};
    static const fc_kernel values[] = {FC_KERNEL_SPHERE, FC_KERNEL_ANISOTROPIC};
    int index;
    fc_code code = fc_cli_parse_choice(spec->name, value, names, &index, err);
    if (code == FC_OK)
        o->settings.kernel = values[index];
    return code;
}

static fc_code set_shadow(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    static const char *const names[] = {"off", "on", NULL};
    int index;
    fc_code code = fc_cli_parse_choice(spec->name, value, names, &index, err);
    if (code == FC_OK)
        o->settings.shadow = (uint32_t)index;
    return code;
}

static fc_code set_density_threshold(fc_snapshot_options *o, const option_spec *spec, const char *value,
                                     fc_error *err)
{
    o->has_density_threshold = true;
    return set_float_setting(o, spec, value, err);
}

/* ---- colour by attribute ---- */

static fc_code set_color_by(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    static const char *const names[] = {"speed", "density", NULL};
    static const fc_color_by values[] = {FC_COLOR_BY_SPEED, FC_COLOR_BY_DENSITY};
    int index;
    fc_code code = fc_cli_parse_choice(spec->name, value, names, &index, err);
    if (code == FC_OK)
        o->settings.color_by = values[index];
    return code;
}

static fc_code set_colormap(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_colormap = true;
    if (!fc_colormap_parse(value, &o->settings.colormap))
        return fc_error_set(err, FC_ERR_USAGE,
                            "%s needs viridis, plasma, inferno, magma, cividis, coolwarm or turbo, not \"%s\"",
                            spec->name, value);
    return FC_OK;
}

/* "MIN:MAX", two finite floats with MIN < MAX (the part before the last
 * ':' is MIN, so negative values need no quoting beyond the shell's). */
static fc_code set_range(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_color_range = true;
    const char *colon = strrchr(value, ':');
    char min_text[64];
    size_t min_len = colon ? (size_t)(colon - value) : 0;
    if (!colon || min_len == 0 || min_len >= sizeof min_text)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs MIN:MAX, not \"%s\"", spec->name, value);
    memcpy(min_text, value, min_len);
    min_text[min_len] = '\0';
    float range[2];
    fc_code code = fc_cli_parse_float(spec->name, min_text, &range[0], err);
    if (code == FC_OK)
        code = fc_cli_parse_float(spec->name, colon + 1, &range[1], err);
    if (code != FC_OK)
        return code;
    if (!(range[0] < range[1]) || !isfinite(range[1] - range[0]))
        return fc_error_set(err, FC_ERR_USAGE, "%s needs MIN below MAX (and a finite width), not \"%s\"",
                            spec->name, value);
    o->settings.color_range[0] = range[0];
    o->settings.color_range[1] = range[1];
    return FC_OK;
}

static fc_code set_iterations(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_iterations = true;
    return fc_cli_parse_uint(spec->name, value, 0, 1000, &o->settings.iterations, err);
}

static fc_code set_aov(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    static const char *const names[] = {"depth", "smoothed-depth", "thickness", "normal", "noise", NULL};
    static const fc_aov values[] = {FC_AOV_DEPTH, FC_AOV_SMOOTHED_DEPTH, FC_AOV_THICKNESS, FC_AOV_NORMAL,
                                    FC_AOV_NOISE};
    int index;
    fc_code code = fc_cli_parse_choice(spec->name, value, names, &index, err);
    if (code == FC_OK)
        o->aov = values[index];
    return code;
}

static fc_code set_quality(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    o->has_quality = true;
    return fc_cli_parse_uint(spec->name, value, 1, 100, &o->quality, err);
}

/* 444 (every pixel's colour, the default) or 420 (one colour per 2x2 pixels:
 * smaller and faster, for streams); sent as the jpeg_subsampling setting. */
static fc_code set_jpeg_subsampling(fc_snapshot_options *o, const option_spec *spec, const char *value,
                                    fc_error *err)
{
    static const char *const names[] = {"444", "420", NULL};
    static const fc_jpeg_subsampling values[] = {FC_JPEG_SUBSAMPLING_YUV444, FC_JPEG_SUBSAMPLING_YUV420};
    int index;
    fc_code code = fc_cli_parse_choice(spec->name, value, names, &index, err);
    if (code == FC_OK) {
        o->has_jpeg_subsampling = true;
        o->settings.jpeg_subsampling = values[index];
    }
    return code;
}

/* ---- scene images: the files are checked once the command line is complete ---- */

static fc_code set_background(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    if (value[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs an image file", spec->name);
    o->background = value;
    return FC_OK;
}

static fc_code set_cubemap(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    if (value[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs six image files or a directory", spec->name);
    o->cubemap = value;
    return FC_OK;
}

static fc_code set_mesh(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    if (o->mesh_count == FC_CLI_MAX_MESHES)
        return fc_error_set(err, FC_ERR_USAGE, "%s: at most %d meshes", spec->name, FC_CLI_MAX_MESHES);
    fc_code code = fc_cli_mesh_parse(value, &o->meshes[o->mesh_count], err);
    if (code == FC_OK)
        o->mesh_count++;
    return code;
}

static fc_code set_read(fc_snapshot_options *o, const option_spec *spec, const char *value, fc_error *err)
{
    return fc_cli_set_read_option(&o->read, spec->name, value, err);
}

#define SETTING(name, handler, field) {name, handler, offsetof(fc_settings, field)}

static const option_spec options[] = {
    {"-o", set_output, 0},
    {"--output", set_output, 0},
    {"--server", set_server, 0},
    {"--size", set_size, 0},
    {"--eye", set_eye, 0},
    {"--target", set_target, 0},
    {"--up", set_up, 0},
    {"--fov", set_fov, 0},
    {"--radius", set_radius, 0},
    {"--smoothing", set_smoothing, 0},
    {"--iterations", set_iterations, 0},
    {"--kernel", set_kernel, 0},
    SETTING("--filter-radius", set_uint_setting, filter_radius),
    SETTING("--smooth-scale", set_float_setting, smooth_scale),
    SETTING("--color", set_rgb_setting, fluid_color),
    SETTING("--absorption", set_rgb_setting, absorption),
    SETTING("--ior", set_float_setting, ior),
    SETTING("--refraction", set_float_setting, refraction),
    SETTING("--specular", set_float_setting, specular),
    SETTING("--shininess", set_float_setting, shininess),
    SETTING("--thickness-scale", set_float_setting, thickness_scale),
    SETTING("--thickness-blur", set_uint_setting, thickness_blur),
    {"--shadow", set_shadow, 0},
    SETTING("--exposure", set_float_setting, exposure),
    SETTING("--noise", set_float_setting, noise),
    SETTING("--foam", set_float_setting, foam),
    SETTING("--foam-tau", set_float_setting, foam_tau),
    SETTING("--foam-decay", set_float_setting, foam_decay),
    SETTING("--density-threshold", set_density_threshold, density_threshold),
    {"--color-by", set_color_by, 0},
    {"--colormap", set_colormap, 0},
    {"--range", set_range, 0},
    {"--background", set_background, 0},
    {"--cubemap", set_cubemap, 0},
    {"--mesh", set_mesh, 0},
    {"--aov", set_aov, 0},
    {"--quality", set_quality, 0},
    {"--jpeg-subsampling", set_jpeg_subsampling, 0},
    {"--dataset", set_read, 0},
    {"--step", set_read, 0},
    {"--select", set_read, 0},
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

void fc_snapshot_set_defaults(fc_snapshot_options *o)
{
    memset(o, 0, sizeof *o);
    o->read.recentring = &o->recentring;
    o->server = FC_DEFAULT_SERVER;
    o->width = 1280;
    o->height = 720;
    o->fov_deg = FC_SNAPSHOT_DEFAULT_FOV;
    fc_settings_default(&o->settings);
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
    if (o->settings.color_by != FC_COLOR_BY_NONE)
        return FC_OK;
    if (o->has_colormap)
        return fc_error_set(err, FC_ERR_USAGE, "--colormap applies with --color-by speed|density");
    if (o->has_color_range)
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
    if (o->has_jpeg_subsampling && o->format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--jpeg-subsampling applies to .jpg/.jpeg output only");
    code = fc_snapshot_check_coloring(o, err);
    return code != FC_OK ? code : fc_snapshot_check_camera(o, err);
}

fc_code fc_snapshot_take_option(fc_snapshot_options *o, int argc, char **argv, int *i, bool *known, fc_error *err)
{
    const char *value;
    const option_spec *spec = find_option(argv[*i], &value);
    *known = spec != NULL;
    if (!spec)
        return FC_OK;
    if (!value) {
        if (*i + 1 >= argc)
            return fc_error_set(err, FC_ERR_USAGE, "%s needs a value", spec->name);
        value = argv[++*i];
    }
    return spec->handle(o, spec, value, err);
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
          "  --jpeg-subsampling 444|420\n"
          "                          JPEG chroma: 444 every pixel's colour (default),\n"
          "                          420 one per 2x2 pixels, smaller and faster\n"
          "\n",
          to);
}

static void print_surface_help(FILE *to, const fc_settings *d)
{
    fprintf(to,
            "fluid surface:\n"
            "  --radius R              particle sphere radius in world units; without it\n"
            "                          the radius is estimated from the particle spacing\n"
            "                          (0.9 x the median nearest-neighbour distance) and\n"
            "                          the radius used is printed\n"
            "  --kernel sphere|anisotropic\n"
            "                          particle shape: spheres, or ellipsoids stretched\n"
            "                          along each particle's neighbours (flat sheets,\n"
            "                          long jets; default %s)\n"
            "  --smoothing MODE        depth smoothing: narrow (narrow-range filter,\n"
            "                          default), curvature (curvature flow), bilateral,\n"
            "                          binomial or none\n"
            "  --iterations N          curvature-flow steps or filter passes, 0..1000\n"
            "                          (default: narrow %u, curvature %u, bilateral %u,\n"
            "                          binomial %u)\n"
            "  --filter-radius PX      kernel half-width of bilateral/binomial/narrow,\n"
            "                          0..64 pixels; 0 = from the particle size (default)\n"
            "  --smooth-scale S        resolution of the smoothing: 1, 0.5 or 0.25\n"
            "                          (default %g)\n"
            "  --noise AMPLITUDE       surface noise, 0..10; 0 = off (default %g)\n"
            "  --foam INTENSITY        foam and spray, 0..10; 0 = off (default %g)\n"
            "  --foam-tau V            velocity change per frame that raises foam, > 0\n"
            "                          (default %g)\n"
            "  --foam-decay F          per-frame decay of raised foam, 0 <= F < 1\n"
            "                          (default %g)\n"
            "  --density-threshold D   particles with density below D are drawn as white\n"
            "                          spray; 0 = off (default: half the frame's median\n"
            "                          density when the file has densities, and printed;\n"
            "                          else off)\n"
            "\n",
            d->kernel == FC_KERNEL_ANISOTROPIC ? "anisotropic" : "sphere",
            fc_smoothing_default_iterations(FC_SMOOTHING_NARROW),
            fc_smoothing_default_iterations(FC_SMOOTHING_CURVATURE),
            fc_smoothing_default_iterations(FC_SMOOTHING_BILATERAL),
            fc_smoothing_default_iterations(FC_SMOOTHING_BINOMIAL), (double)d->smooth_scale, (double)d->noise, (double)d->foam,
            (double)d->foam_tau, (double)d->foam_decay);
}

static void print_shading_help(FILE *to, const fc_settings *d)
{
    fprintf(to,
            "shading:\n"
            "  --color R,G,B           linear colour of a thick layer, each 0..1\n"
            "                          (default %g,%g,%g)\n"
            "  --absorption R,G,B      Beer-Lambert absorption per particle radius of\n"
            "                          thickness, >= 0 (default %g,%g,%g)\n"
            "  --ior N                 index of refraction, 1..3 (default %g)\n"
            "  --refraction G          background offset per pixel of projected\n"
            "                          thickness, 0..1000 (default %g)\n"
            "  --specular S            specular intensity, 0..10 (default %g)\n"
            "  --shininess E           specular exponent, 1..10000 (default %g)\n"
            "  --thickness-scale S     resolution of the thickness pass: 1, 0.5 or 0.25\n"
            "                          (default %g)\n"
            "  --thickness-blur PX     blur radius of the thickness, 0..32 pixels\n"
            "                          (default %u)\n"
            "  --shadow on|off         the fluid's soft shadow on the built-in floor\n"
            "                          (default %s)\n"
            "  --exposure EV           stops of exposure before the filmic tone map,\n"
            "                          -16..16 (default %g)\n"
            "  --background IMAGE      PNG, JPEG or EXR image behind the fluid (and seen\n"
            "                          through it) instead of the built-in floor and sky\n"
            "  --cubemap PX,NX,PY,NY,PZ,NZ\n"
            "                          six square images of one size (+X -X +Y -Y +Z -Z)\n"
            "                          reflected in the fluid instead of the built-in sky;\n"
            "  --cubemap DIR           or a directory holding px, nx, py, ny, pz and nz\n"
            "                          .png/.jpg/.jpeg/.exr\n"
            "                          (scene images: at most 8192 pixels per side)\n"
            "  --mesh FILE[:color=R,G,B][:opacity=X][:hide-near][:transforms=PLACEMENTS]\n"
            "                          a triangle mesh drawn with the fluid (repeatable, up\n"
            "                          to 16): .obj, .stl, .ply (with faces), legacy .vtk\n"
            "                          POLYDATA or .vtp; colour linear RGB 0..1 (default 0.8\n"
            "                          grey); opacity 1 (default) hides the fluid behind it,\n"
            "                          below 1 is glass over it; hide-near leaves out the\n"
            "                          faces turned toward the camera (a tank's near walls).\n"
            "                          A FILE with %%d (box_%%04d.obj) is read per frame by\n"
            "                          render, with the frame's number; a static FILE moves\n"
            "                          by PLACEMENTS, lines \"FRAME m00 .. m23\" (3x4 matrix)\n"
            "\n",
            (double)d->fluid_color[0], (double)d->fluid_color[1], (double)d->fluid_color[2],
            (double)d->absorption[0], (double)d->absorption[1], (double)d->absorption[2], (double)d->ior,
            (double)d->refraction, (double)d->specular, (double)d->shininess, (double)d->thickness_scale,
            (unsigned)d->thickness_blur, d->shadow ? "on" : "off", (double)d->exposure);
}

static void print_color_help(FILE *to)
{
    fputs("colour by attribute:\n"
          "  --color-by speed|density\n"
          "                          tint the fluid by each particle's speed (needs\n"
          "                          velocities) or density (needs densities): the\n"
          "                          colours are splatted and blurred with the thickness\n"
          "                          and thick fluid shows them; a frame without the\n"
          "                          attribute is an error\n"
          "  --colormap NAME         viridis (default), plasma, inferno, magma, cividis,\n"
          "                          coolwarm or turbo\n"
          "  --range MIN:MAX         attribute values at the map's ends, MIN < MAX;\n"
          "                          values outside take the end colours. Default: the\n"
          "                          first frame's 2nd to 98th percentile, printed, so\n"
          "                          that later runs can fix it and compare\n"
          "  --legend                draw a colour bar with the attribute's name and five\n"
          "                          tick labels into the image's top-right corner\n"
          "                          (snapshot only; drawn by the client with FreeType)\n"
          "\n",
          to);
}

void fc_snapshot_print_settings_help(FILE *to)
{
    fc_settings defaults;
    fc_settings_default(&defaults);
    print_surface_help(to, &defaults);
    print_shading_help(to, &defaults);
    print_color_help(to);
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
    fc_cli_print_read_options_help(to);
    fc_snapshot_print_settings_help(to);
    fputs("  -h, --help              show this help\n\n", to);
    fc_cli_print_exit_codes(to);
}
