/* bench_options.c — parses the fluidcast-bench command line. */
#include "bench_options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_options.h"

static const struct {
    const char *name;
    fc_smoothing value;
} smoothing_names[] = {
    {"none", FC_SMOOTHING_NONE},
    {"curvature", FC_SMOOTHING_CURVATURE},
    {"bilateral", FC_SMOOTHING_BILATERAL},
    {"binomial", FC_SMOOTHING_BINOMIAL},
    {"narrow", FC_SMOOTHING_NARROW},
};
#define N_SMOOTHING_NAMES (sizeof smoothing_names / sizeof smoothing_names[0])

const char *bench_smoothing_name(fc_smoothing s)
{
    for (size_t i = 0; i < N_SMOOTHING_NAMES; i++)
        if (smoothing_names[i].value == s)
            return smoothing_names[i].name;
    return "?";
}

void bench_options_print_usage(void)
{
    printf("usage: fluidcast-bench [--gpu auto|software|N] [--particles 16k,64k,...]\n"
           "         [--size 1280x720,...] [--smoothing curvature,none,...] [--iterations 15,40,default,...]\n"
           "         [--scale 1,0.5,0.25] [--frames N] [--encode png|jpeg|exr|none] [--image PATH.png]\n"
           "         [--profile] [--shader-dir DIR] [--splat auto|fragment|compute] [--filter-radius PX]\n"
           "         [--kernel sphere|anisotropic] [--shadow on|off] [--thickness-scale 1|0.5|0.25]\n"
           "         [--constants auto|uniforms|flat]\n"
           "       fluidcast-bench --particles N --write-scene PATH.f32\n"
           "Prints a markdown table: median GPU ms per stage (timer queries; upload: the GL thread's\n"
           "wall time copying the frame), encode ms, wall ms, and\n"
           "the GPU MiB the pipeline holds after the row's frames (its own count from the sizes and\n"
           "formats it allocated; the driver's next to it where GL_NVX_gpu_memory_info reports one).\n"
           "A value may follow the option or an '='.\n"
           "Every combination of the lists runs; --iterations default: each method's own default;\n"
           "--scale: the resolution of depth smoothing, as a fraction of the image's.\n"
           "--smoothing:");
    for (size_t i = 0; i < N_SMOOTHING_NAMES; i++)
        printf(" %s", smoothing_names[i].name);
    printf("\n--image writes each configuration's last frame there, so it ends up with the last one's.\n"
           "--profile prints after each row where its time goes: every pass's wall time with the GL\n"
           "queue drained around it, the process's CPU time over it (on llvmpipe: the pass's work,\n"
           "steadier than wall time on a loaded machine), its fragment shader invocations, the\n"
           "sprites' sizes, and the GPU memory split into particle buffers, render targets and the\n"
           "readback buffer.\n"
           "--shader-dir loads the *.glsl files from DIR, to time shader changes without rebuilding.\n"
           "--filter-radius sets the kernel half-width in pixels of the bilateral, binomial and\n"
           "narrow-range filters (default 0: from the projected particle size).\n"
           "--splat forces the surface splat: sprites through the rasterizer or the compute splat\n"
           "(default auto: the pipeline's choice by sprite size).\n"
           "--kernel anisotropic splats Yu & Turk's ellipsoids (default sphere); the ellipsoids are\n"
           "computed once per upload, so the rows time their splat; before the rows of each\n"
           "particle count a line gives the anisotropy passes' own time (median over --frames\n"
           "fresh computations, the GL queue drained around each).\n"
           "--shadow off leaves out the fluid's shadow on the floor (default on, as rendered).\n"
           "--thickness-scale sets the thickness splat's resolution (default: fluidcast's).\n"
           "--constants: how the full-screen passes' fragment shaders get their per-draw values\n"
           "(default auto: flat inputs on llvmpipe, uniforms on a GPU; the images are the same).\n"
           "--write-scene writes the drop scene as raw little-endian float32 xyz and prints\n"
           "'particles N spacing S radius R' (R: the sphere radius the benchmark renders with).\n");
}

void bench_options_default(bench_options *o)
{
    const bench_options defaults = {
        .action = BENCH_RUN,
        .gpu = {FC_GPU_AUTO, 0},
        .particles = {65536}, .n_particles = 1,
        .sizes = {{1280, 720}}, .n_sizes = 1,
        .smoothings = {FC_SMOOTHING_CURVATURE}, .n_smoothings = 1,
        .iterations = {40}, .n_iterations = 1,
        .smooth_scales = {1.0f}, .n_smooth_scales = 1,
        .frames = 10,
        .format = FC_FORMAT_PNG,
        .shadow = true,
    };
    *o = defaults;
}

/* "16k" -> 16384, "1m" -> 1048576, "5000" -> 5000. */
static int parse_count(const char *s, uint64_t *out)
{
    char *end;
    const double v = strtod(s, &end);
    uint64_t scale = 1;
    if (*end == 'k' || *end == 'K')
        scale = 1024, end++;
    else if (*end == 'm' || *end == 'M')
        scale = 1024 * 1024, end++;
    if (end == s || *end != '\0' || !(v * (double)scale >= 1.0 && v * (double)scale < 1e15))
        return -1;
    *out = (uint64_t)(v * (double)scale);
    return 0;
}

static int parse_particles(const char *item, bench_options *o)
{
    return parse_count(item, &o->particles[o->n_particles++]);
}

static int parse_size(const char *item, bench_options *o)
{
    uint32_t *wh = o->sizes[o->n_sizes++];
    char tail;
    return sscanf(item, "%ux%u%c", &wh[0], &wh[1], &tail) == 2 && wh[0] && wh[1] ? 0 : -1;
}

static int parse_smoothing(const char *item, bench_options *o)
{
    for (size_t k = 0; k < N_SMOOTHING_NAMES; k++)
        if (!strcmp(smoothing_names[k].name, item)) {
            o->smoothings[o->n_smoothings++] = smoothing_names[k].value;
            return 0;
        }
    return -1;
}

static int parse_iterations(const char *item, bench_options *o)
{
    if (!strcmp(item, "default")) {
        o->iterations[o->n_iterations++] = BENCH_DEFAULT_ITERATIONS;
        return 0;
    }
    char *end;
    const unsigned long n = strtoul(item, &end, 10);
    o->iterations[o->n_iterations++] = (uint32_t)n;
    return end != item && *end == '\0' && n <= 1000 ? 0 : -1;
}

/* The resolutions fc_settings_validate accepts; any other would fail every frame. */
static int parse_smooth_scale(const char *item, bench_options *o)
{
    char *end;
    const float v = strtof(item, &end);
    o->smooth_scales[o->n_smooth_scales++] = v;
    return end != item && *end == '\0' && (v == 1.0f || v == 0.5f || v == 0.25f) ? 0 : -1;
}

/* Splits a comma-separated value and hands each item to parse_item, which
 * appends to the list whose length is *count (reset first). */
static fc_code parse_list(const char *option, const char *value, int *count,
                          int (*parse_item)(const char *, bench_options *), bench_options *o, fc_error *err)
{
    char buf[512];
    if (snprintf(buf, sizeof buf, "%s", value) >= (int)sizeof buf)
        return fc_error_set(err, FC_ERR_USAGE, "%s: value too long", option);
    *count = 0;
    for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
        if (*count == BENCH_MAX_LIST)
            return fc_error_set(err, FC_ERR_USAGE, "%s: at most %d values", option, BENCH_MAX_LIST);
        if (parse_item(t, o) != 0)
            return fc_error_set(err, FC_ERR_USAGE, "%s: bad value '%s'", option, t);
    }
    return *count ? FC_OK : fc_error_set(err, FC_ERR_USAGE, "%s: empty list", option);
}

/* A whole number lo..hi for `option`. */
static fc_code parse_bounded(const char *option, const char *value, long lo, long hi, long *out, fc_error *err)
{
    char *end;
    const long n = strtol(value, &end, 10);
    if (end == value || *end != '\0' || n < lo || n > hi)
        return fc_error_set(err, FC_ERR_USAGE, "%s must be %ld..%ld, not '%s'", option, lo, hi, value);
    *out = n;
    return FC_OK;
}

static fc_code set_frames(void *o, const char *name, const char *value, fc_error *err)
{
    long n = 0;
    fc_code code = parse_bounded(name, value, 1, 10000, &n, err);
    if (code == FC_OK)
        ((bench_options *)o)->frames = (int)n;
    return code;
}

/* fc_settings_validate allows kernels up to 64 pixels. */
static fc_code set_filter_radius(void *o, const char *name, const char *value, fc_error *err)
{
    long n = 0;
    fc_code code = parse_bounded(name, value, 0, 64, &n, err);
    if (code == FC_OK)
        ((bench_options *)o)->filter_radius = (uint32_t)n;
    return code;
}

static fc_code parse_encoding(const char *value, bench_options *o, fc_error *err)
{
    static const struct { const char *name; fc_image_format format; } formats[] = {
        {"png", FC_FORMAT_PNG}, {"jpeg", FC_FORMAT_JPEG}, {"exr", FC_FORMAT_EXR}, {"none", 0},
    };
    for (size_t k = 0; k < sizeof formats / sizeof formats[0]; k++)
        if (!strcmp(formats[k].name, value)) {
            o->format = formats[k].format;
            return FC_OK;
        }
    return fc_error_set(err, FC_ERR_USAGE, "--encode: unknown encoding '%s'", value);
}

static fc_code parse_splat(const char *value, bench_options *o, fc_error *err)
{
    if (!strcmp(value, "auto"))
        o->splat = FC_SPLAT_AUTO;
    else if (!strcmp(value, "fragment"))
        o->splat = FC_SPLAT_FRAGMENT;
    else if (!strcmp(value, "compute"))
        o->splat = FC_SPLAT_COMPUTE;
    else
        return fc_error_set(err, FC_ERR_USAGE, "--splat %s: expected auto, fragment or compute", value);
    return FC_OK;
}

static fc_code parse_kernel(const char *value, bench_options *o, fc_error *err)
{
    if (!strcmp(value, "sphere"))
        o->kernel = FC_KERNEL_SPHERE;
    else if (!strcmp(value, "anisotropic"))
        o->kernel = FC_KERNEL_ANISOTROPIC;
    else
        return fc_error_set(err, FC_ERR_USAGE, "--kernel %s: expected sphere or anisotropic", value);
    return FC_OK;
}

static fc_code parse_shadow(const char *value, bench_options *o, fc_error *err)
{
    if (!strcmp(value, "on") || !strcmp(value, "off")) {
        o->shadow = !strcmp(value, "on");
        return FC_OK;
    }
    return fc_error_set(err, FC_ERR_USAGE, "--shadow %s: expected on or off", value);
}

/* The resolutions fc_settings_validate accepts for the thickness. */
static fc_code parse_thickness_scale(const char *value, bench_options *o, fc_error *err)
{
    char *end = NULL;
    float v = strtof(value, &end);
    if (end == value || *end != '\0' || (v != 1.0f && v != 0.5f && v != 0.25f))
        return fc_error_set(err, FC_ERR_USAGE, "--thickness-scale %s: expected 1, 0.5 or 0.25", value);
    o->thickness_scale = v;
    return FC_OK;
}

static fc_code parse_constants(const char *value, bench_options *o, fc_error *err)
{
    if (!strcmp(value, "auto"))
        o->constants = FC_CONSTANTS_AUTO;
    else if (!strcmp(value, "uniforms"))
        o->constants = FC_CONSTANTS_UNIFORMS;
    else if (!strcmp(value, "flat"))
        o->constants = FC_CONSTANTS_FLAT;
    else
        return fc_error_set(err, FC_ERR_USAGE, "--constants %s: expected auto, uniforms or flat", value);
    return FC_OK;
}

static fc_code set_gpu(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return fc_gpu_choice_parse(value, &((bench_options *)o)->gpu, err);
}

static fc_code set_particles(void *target, const char *name, const char *value, fc_error *err)
{
    bench_options *o = target;
    return parse_list(name, value, &o->n_particles, parse_particles, o, err);
}

static fc_code set_sizes(void *target, const char *name, const char *value, fc_error *err)
{
    bench_options *o = target;
    return parse_list(name, value, &o->n_sizes, parse_size, o, err);
}

static fc_code set_smoothings(void *target, const char *name, const char *value, fc_error *err)
{
    bench_options *o = target;
    return parse_list(name, value, &o->n_smoothings, parse_smoothing, o, err);
}

static fc_code set_iterations(void *target, const char *name, const char *value, fc_error *err)
{
    bench_options *o = target;
    return parse_list(name, value, &o->n_iterations, parse_iterations, o, err);
}

static fc_code set_smooth_scales(void *target, const char *name, const char *value, fc_error *err)
{
    bench_options *o = target;
    return parse_list(name, value, &o->n_smooth_scales, parse_smooth_scale, o, err);
}

static fc_code set_encoding(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return parse_encoding(value, o, err);
}

static fc_code set_shader_dir(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((bench_options *)o)->shader_dir = value;
    return FC_OK;
}

static fc_code set_splat(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return parse_splat(value, o, err);
}

static fc_code set_kernel(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return parse_kernel(value, o, err);
}

static fc_code set_shadow(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return parse_shadow(value, o, err);
}

static fc_code set_thickness_scale(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return parse_thickness_scale(value, o, err);
}

static fc_code set_constants(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return parse_constants(value, o, err);
}

static fc_code set_image(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((bench_options *)o)->image_path = value;
    return FC_OK;
}

static fc_code set_write_scene(void *target, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    bench_options *o = target;
    o->action = BENCH_WRITE_SCENE;
    o->scene_path = value;
    return FC_OK;
}

static fc_code set_profile(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((bench_options *)o)->profile = 1;
    return FC_OK;
}

/* The options; their help is bench_options_print_usage's prose. */
static const fc_option options[] = {
    {"--gpu", "auto|software|N", set_gpu, NULL, NULL},
    {"--particles", "LIST", set_particles, NULL, NULL},
    {"--size", "LIST", set_sizes, NULL, NULL},
    {"--smoothing", "LIST", set_smoothings, NULL, NULL},
    {"--iterations", "LIST", set_iterations, NULL, NULL},
    {"--scale", "LIST", set_smooth_scales, NULL, NULL},
    {"--frames", "N", set_frames, NULL, NULL},
    {"--encode", "FORMAT", set_encoding, NULL, NULL},
    {"--shader-dir", "DIR", set_shader_dir, NULL, NULL},
    {"--splat", "METHOD", set_splat, NULL, NULL},
    {"--filter-radius", "PX", set_filter_radius, NULL, NULL},
    {"--kernel", "KERNEL", set_kernel, NULL, NULL},
    {"--shadow", "on|off", set_shadow, NULL, NULL},
    {"--thickness-scale", "SCALE", set_thickness_scale, NULL, NULL},
    {"--constants", "MODE", set_constants, NULL, NULL},
    {"--image", "PATH", set_image, NULL, NULL},
    {"--write-scene", "PATH", set_write_scene, NULL, NULL},
    {"--profile", NULL, set_profile, NULL, NULL},
};

static const fc_option_table table = {"fluidcast-bench", options, sizeof options / sizeof options[0], NULL, NULL};

fc_code bench_options_parse(int argc, char **argv, bench_options *o, fc_error *err)
{
    bool help = false;
    fc_code code = fc_options_parse(&table, argc - 1, argv + 1, o, &help, err);
    if (code != FC_OK)
        return code;
    if (help) {
        o->action = BENCH_HELP;
        return FC_OK;
    }
    if (o->action == BENCH_WRITE_SCENE && o->n_particles != 1)
        return fc_error_set(err, FC_ERR_USAGE, "--write-scene takes exactly one --particles count");
    return FC_OK;
}
