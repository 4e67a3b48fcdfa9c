/* render_debug.c — renders a raw .f32 particle file to a binary PPM (colour,
 * normals mapped to RGB) or PGM (other AOVs: depths stretched to 0..255,
 * thickness from black up, noise around mid-grey; PFM keeps the floats) so a
 * person can look at the pipeline's output; not a test. Convert with e.g.
 * `oiiotool out.ppm -o out.png`.
 *
 * usage: fc_render_debug in.f32 out.ppm|out.pgm|out.pfm width height radius
 *        eye_x eye_y eye_z target_x target_y target_z up_x up_y up_z fov_y
 *        [color|depth|smoothed|thickness|normal|noise] [key=value ...]
 * keys: iterations, noise, foam, foam_tau, foam_decay, refraction, specular,
 *       shininess, thickness_scale, thickness_blur, smooth_scale, smoothing
 *       (none|curvature|bilateral|binomial|narrow or 0-4), filter_radius,
 *       kick=x,y,z,r (two frames: particles within r of the point get a
 *       velocity jump, so the foam state raises their noise).
 * FC_SHADER_DIR, when set, loads the shaders from that directory instead of
 * the built-in copies, to try shader changes without rebuilding. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl_context.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "pipeline.h"

typedef struct kick {
    int on;
    float centre[3];
    float radius;
} kick;

static int read_f32(const char *path, fc_frame *frame)
{
    FILE *f = fopen(path, "rb");
    if (!f || fseek(f, 0, SEEK_END) != 0)
        return 0;
    long bytes = ftell(f);
    rewind(f);
    fc_error err;
    /* Velocities and ids for the foam state; set_velocities fills them. */
    uint32_t attributes = FC_ATTR_VELOCITY | FC_ATTR_IDS;
    int ok = bytes > 0 && fc_frame_alloc(frame, (uint64_t)bytes / 12, attributes, &err) == FC_OK &&
             fread(frame->positions, 12, frame->count, f) == frame->count;
    fclose(f);
    return ok;
}

static fc_aov parse_aov(const char *name)
{
    const char *names[] = {"color", "depth", "smoothed", "thickness", "normal", "noise"};
    for (int i = 0; i < (int)(sizeof names / sizeof names[0]); i++)
        if (strcmp(name, names[i]) == 0)
            return (fc_aov)i;
    return FC_AOV_COLOR;
}

/* A smoothing method by name or number; an unknown name passes on as an
 * invalid method for the pipeline to reject with a message. */
static fc_smoothing parse_smoothing(const char *value)
{
    const char *names[] = {"none", "curvature", "bilateral", "binomial", "narrow"};
    for (int i = 0; i < (int)(sizeof names / sizeof names[0]); i++)
        if (strcmp(value, names[i]) == 0)
            return (fc_smoothing)i;
    char *end = NULL;
    long number = strtol(value, &end, 10);
    return end != value && *end == '\0' ? (fc_smoothing)number : (fc_smoothing)-1;
}

/* Applies one key=value argument; 0 when the key is unknown. */
static int parse_setting(const char *arg, fc_settings *s, kick *k)
{
    const char *eq = strchr(arg, '=');
    if (!eq)
        return 0;
    size_t n = (size_t)(eq - arg);
    const char *v = eq + 1;
    struct { const char *key; float *field; } floats[] = {
        {"noise", &s->noise}, {"foam", &s->foam}, {"foam_tau", &s->foam_tau}, {"foam_decay", &s->foam_decay},
        {"refraction", &s->refraction}, {"specular", &s->specular}, {"shininess", &s->shininess},
        {"thickness_scale", &s->thickness_scale}, {"smooth_scale", &s->smooth_scale},
        {"density_threshold", &s->density_threshold}};
    for (size_t i = 0; i < sizeof floats / sizeof floats[0]; i++)
        if (strlen(floats[i].key) == n && strncmp(arg, floats[i].key, n) == 0) {
            *floats[i].field = strtof(v, NULL);
            return 1;
        }
    if (strncmp(arg, "iterations=", 11) == 0)
        s->iterations = (uint32_t)atoi(v);
    else if (strncmp(arg, "thickness_blur=", 15) == 0)
        s->thickness_blur = (uint32_t)atoi(v);
    else if (strncmp(arg, "smoothing=", 10) == 0)
        s->smoothing = parse_smoothing(v);
    else if (strncmp(arg, "filter_radius=", 14) == 0)
        s->filter_radius = (uint32_t)atoi(v);
    else if (strncmp(arg, "kick=", 5) == 0)
        k->on = sscanf(v, "%f,%f,%f,%f", &k->centre[0], &k->centre[1], &k->centre[2], &k->radius) == 4;
    else
        return 0;
    return 1;
}

static void write_ppm(FILE *out, const fc_image *img)
{
    fprintf(out, "P6\n%u %u\n255\n", img->width, img->height);
    const unsigned char *rgba = img->pixels;
    for (size_t i = 0; i < (size_t)img->width * img->height; i++)
        fwrite(rgba + 4 * i, 1, 3, out);
}

/* Normals as colours: each component from [-1, 1] to [0, 255]; no fluid stays black. */
static void write_normal_ppm(FILE *out, const fc_image *img)
{
    fprintf(out, "P6\n%u %u\n255\n", img->width, img->height);
    const float *n = img->pixels;
    for (size_t i = 0; i < (size_t)img->width * img->height; i++) {
        int fluid = n[3 * i] != 0.0f || n[3 * i + 1] != 0.0f || n[3 * i + 2] != 0.0f;
        for (int c = 0; c < 3; c++)
            fputc(fluid ? (int)lroundf(127.5f * (n[3 * i + c] + 1.0f)) : 0, out);
    }
}

/* Little-endian greyscale PFM: the float values as they are, rows bottom to top. */
static void write_pfm(FILE *out, const fc_image *img)
{
    fprintf(out, "Pf\n%u %u\n-1.0\n", img->width, img->height);
    const float *v = img->pixels;
    for (uint32_t row = img->height; row-- > 0;)
        fwrite(v + (size_t)row * img->width, sizeof(float), img->width, out);
}

/* Signed values around mid-grey, the largest magnitude at black or white. */
static void write_signed_pgm(FILE *out, const fc_image *img)
{
    const float *v = img->pixels;
    size_t n = (size_t)img->width * img->height;
    float peak = 1e-30f;
    for (size_t i = 0; i < n; i++)
        peak = fabsf(v[i]) > peak ? fabsf(v[i]) : peak;
    fprintf(out, "P5\n%u %u\n255\n", img->width, img->height);
    for (size_t i = 0; i < n; i++)
        fputc((int)lroundf(127.5f + 127.5f * v[i] / peak), out);
}

/* From 0 (black) to the largest value (white). */
static void write_scaled_pgm(FILE *out, const fc_image *img)
{
    const float *v = img->pixels;
    size_t n = (size_t)img->width * img->height;
    float hi = 1e-30f;
    for (size_t i = 0; i < n; i++)
        hi = v[i] > hi ? v[i] : hi;
    fprintf(out, "P5\n%u %u\n255\n", img->width, img->height);
    for (size_t i = 0; i < n; i++)
        fputc((int)lroundf(255.0f * fmaxf(v[i], 0.0f) / hi), out);
}

/* Stretches the non-zero values over 1..255 so small depth differences show; 0 stays black. */
static void write_pgm(FILE *out, const fc_image *img)
{
    const float *v = img->pixels;
    size_t n = (size_t)img->width * img->height;
    float lo = FLT_MAX, hi = 0.0f;
    for (size_t i = 0; i < n; i++)
        if (v[i] > 0.0f) {
            lo = v[i] < lo ? v[i] : lo;
            hi = v[i] > hi ? v[i] : hi;
        }
    fprintf(out, "P5\n%u %u\n255\n", img->width, img->height);
    for (size_t i = 0; i < n; i++) {
        unsigned char g = v[i] > 0.0f ? (unsigned char)(1.0f + 254.0f * (hi - v[i]) / (hi - lo + 1e-30f)) : 0;
        fputc(g, out);
    }
}

static void write_image(FILE *out, const char *path, fc_aov aov, const fc_image *img)
{
    const char *extension = strrchr(path, '.');
    if (aov == FC_AOV_COLOR)
        write_ppm(out, img);
    else if (aov == FC_AOV_NORMAL)
        write_normal_ppm(out, img);
    else if (extension && strcmp(extension, ".pfm") == 0)
        write_pfm(out, img);
    else if (aov == FC_AOV_NOISE)
        write_signed_pgm(out, img);
    else if (aov == FC_AOV_THICKNESS)
        write_scaled_pgm(out, img);
    else
        write_pgm(out, img);
}

/* Velocities of a frame at rest, or with the particles near the kick moving by one unit per frame. */
static void set_velocities(fc_frame *frame, const kick *k, int kicked)
{
    for (uint64_t i = 0; i < frame->count; i++) {
        const float *p = frame->positions + 3 * i;
        float d[3] = {p[0] - k->centre[0], p[1] - k->centre[1], p[2] - k->centre[2]};
        int near = kicked && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < k->radius * k->radius;
        frame->ids[i] = (uint32_t)i;
        for (int c = 0; c < 3; c++)
            frame->velocity[3 * i + c] = near ? (c == 2 ? 1.0f : 0.0f) : 0.0f;
    }
}

/* Uploads the frame and advances the foam state: twice with a kick (at rest, then kicked). */
static fc_code upload(fc_pipeline *pipeline, fc_foam_state *foam, fc_frame *frame, const fc_settings *settings,
                      const kick *k, float *upload_ms, fc_error *err)
{
    fc_code code = FC_OK;
    for (int step = k->on ? 0 : 1; step < 2 && code == FC_OK; step++) {
        set_velocities(frame, k, step == 1 && k->on);
        code = fc_pipeline_upload(pipeline, frame, upload_ms, err);
        if (code == FC_OK)
            code = fc_foam_state_advance(foam, pipeline, frame, settings, err);
    }
    return code;
}

int main(int argc, char **argv)
{
    if (argc < 16) {
        fprintf(stderr, "usage: %s in.f32 out width height radius eye(3) target(3) up(3) fov_y "
                        "[color|depth|smoothed|thickness|normal|noise] [key=value ...]\n", argv[0]);
        return 2;
    }
    fc_camera cam = {.width = (uint32_t)atoi(argv[3]), .height = (uint32_t)atoi(argv[4])};
    for (int i = 0; i < 3; i++) {
        cam.eye[i] = strtof(argv[6 + i], NULL);
        cam.target[i] = strtof(argv[9 + i], NULL);
        cam.up[i] = strtof(argv[12 + i], NULL);
    }
    cam.fov_y_deg = strtof(argv[15], NULL);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = strtof(argv[5], NULL);
    fc_aov aov = argc > 16 ? parse_aov(argv[16]) : FC_AOV_COLOR;
    kick k = {0};
    for (int i = 17; i < argc; i++)
        if (!parse_setting(argv[i], &settings, &k)) {
            fprintf(stderr, "unknown setting %s\n", argv[i]);
            return 2;
        }

    fc_frame frame = {0};
    if (!read_f32(argv[1], &frame)) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 1;
    }
    fc_gpu_choice gpu = {FC_GPU_AUTO, 0};
    fc_gl_context *gl = NULL;
    fc_pipeline *pipeline = NULL;
    fc_foam_state *foam = NULL;
    fc_image img = {0};
    fc_error err = {0};
    float upload_ms = -1.0f, stage_ms[FC_STAGE_COUNT];
    fc_code code = fc_gl_context_create(&gpu, &gl, &err);
    if (code == FC_OK)
        code = fc_pipeline_create(&(fc_pipeline_config){.shader_dir = getenv("FC_SHADER_DIR")}, &pipeline, &err);
    if (code == FC_OK)
        code = fc_foam_state_create(&foam, &err);
    if (code == FC_OK)
        code = upload(pipeline, foam, &frame, &settings, &k, &upload_ms, &err);
    if (code == FC_OK)
        code = fc_pipeline_render(pipeline, &cam, &settings, aov, 1, &img, stage_ms, &err);
    FILE *out = code == FC_OK ? fopen(argv[2], "wb") : NULL;
    if (out) {
        write_image(out, argv[2], aov, &img);
        fclose(out);
        printf("%s: %llu particles, upload %.2f ms, depth %.2f, thickness %.2f, smoothing %.2f, "
               "composite %.2f, readback %.2f ms\n", fc_gl_context_renderer(gl), (unsigned long long)frame.count,
               upload_ms, stage_ms[FC_STAGE_DEPTH], stage_ms[FC_STAGE_THICKNESS], stage_ms[FC_STAGE_SMOOTHING],
               stage_ms[FC_STAGE_COMPOSITE], stage_ms[FC_STAGE_READBACK]);
    } else {
        fprintf(stderr, "%s\n", code == FC_OK ? "cannot write the output" : err.message);
    }
    fc_image_free(&img);
    fc_foam_state_destroy(foam);
    fc_pipeline_destroy(pipeline);
    fc_gl_context_destroy(gl);
    fc_frame_free(&frame);
    return out ? 0 : 1;
}
