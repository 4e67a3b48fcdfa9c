/* fluidcast-bench — per-stage timings of the render pipeline without a socket.
 *
 * For every combination of particle count, image size, smoothing method,
 * iteration count and smoothing resolution it renders a warm-up frame and then
 * --frames measured ones, and prints one markdown table row with the median GPU
 * time of each stage (timer queries; the upload by the clock), the encode time,
 * the wall time per frame and the GPU memory the pipeline holds afterwards
 * (bench_memory.h).
 * --write-scene exports the particles instead, for the peer benchmark (bench/peer/). */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench_memory.h"
#include "bench_options.h"
#include "bench_profile.h"
#include "bench_output.h"
#include "egl_context.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "image_encoder.h"
#include "pipeline.h"
#include "pipeline_internal.h"
#include "scene.h"

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int compare_float(const void *a, const void *b)
{
    const float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static float median(float *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_float);
    return n % 2 ? v[n / 2] : 0.5f * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct bench_row {
    float stage[FC_STAGE_COUNT];
    float wall;
} bench_row;

/* Renders (and encodes) one frame; stage_ms[FC_STAGE_ENCODE] is -1 without encoding. */
static fc_code render_frame(fc_pipeline *pipe, const bench_options *o, const fc_camera *cam,
                            const fc_settings *settings, fc_image *img, fc_buf *encoded,
                            float stage_ms[FC_STAGE_COUNT], fc_error *err)
{
    fc_code rc = fc_pipeline_render(pipe, cam, settings, FC_AOV_COLOR, o->format != FC_FORMAT_EXR, img,
                                    stage_ms, err);
    stage_ms[FC_STAGE_ENCODE] = -1.0f;
    if (rc != FC_OK || !o->format)
        return rc;
    const double e0 = now_ms();
    fc_buf_reset(encoded);
    rc = fc_encode_image(img, o->format, FC_DEFAULT_QUALITY, encoded, err);
    stage_ms[FC_STAGE_ENCODE] = (float)(now_ms() - e0);
    return rc;
}

/* Outside the timed frames: the encoder may be set to another format, or none. */
static fc_code save_png(const fc_image *img, fc_buf *encoded, const char *path, fc_error *err)
{
    fc_buf_reset(encoded);
    fc_code rc = fc_encode_image(img, FC_FORMAT_PNG, FC_DEFAULT_QUALITY, encoded, err);
    return rc == FC_OK ? bench_write_bytes(encoded->data, encoded->len, path, err) : rc;
}

/* Renders one configuration: a warm-up frame, then o->frames measured frames;
 * the row gets the median of each stage and of the wall time. */
static fc_code bench_config(fc_pipeline *pipe, const bench_options *o, uint32_t w, uint32_t h,
                            const fc_settings *settings, bench_row *row, fc_error *err)
{
    fc_camera cam;
    bench_scene_drop_camera(w, h, &cam);
    fc_image img = {0};
    fc_buf encoded;
    fc_buf_init(&encoded);
    /* one series of o->frames samples per stage, then one for the wall time */
    float *samples = calloc((size_t)o->frames * (FC_STAGE_COUNT + 1), sizeof *samples);
    fc_code rc = samples ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "out of memory");
    for (int f = -1; rc == FC_OK && f < o->frames; f++) {
        float stage_ms[FC_STAGE_COUNT];
        const double t0 = now_ms();
        rc = render_frame(pipe, o, &cam, settings, &img, &encoded, stage_ms, err);
        if (f < 0)
            continue; /* warm-up: shader variants, allocation at this size */
        for (int s = 0; s < FC_STAGE_COUNT; s++)
            samples[(size_t)s * o->frames + f] = stage_ms[s];
        samples[(size_t)FC_STAGE_COUNT * o->frames + f] = (float)(now_ms() - t0);
    }
    if (rc == FC_OK && o->image_path)
        rc = save_png(&img, &encoded, o->image_path, err);
    if (rc == FC_OK) {
        for (int s = 0; s < FC_STAGE_COUNT; s++)
            row->stage[s] = median(samples + (size_t)s * o->frames, o->frames);
        row->wall = median(samples + (size_t)FC_STAGE_COUNT * o->frames, o->frames);
    }
    free(samples);
    fc_buf_free(&encoded);
    fc_image_free(&img);
    return rc;
}

static void print_ms(float v)
{
    if (v < 0)
        printf(" – |");
    else
        printf(" %.2f |", v);
}

static void print_header(void)
{
    printf("| particles | size | smoothing | iter | scale | upload | depth | thickness | smoothing | composite |"
           " readback | encode | GPU sum | wall/frame | fps | GPU MiB |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

static void print_row(uint64_t particles, uint32_t w, uint32_t h, const fc_settings *settings, float upload_ms,
                      const bench_row *row, const bench_memory *memory, const fc_pipeline *pipe)
{
    float gpu = 0.0f;
    for (int s = FC_STAGE_DEPTH; s <= FC_STAGE_READBACK; s++)
        gpu += row->stage[s] > 0 ? row->stage[s] : 0.0f;
    printf("| %llu | %ux%u | %s | %u | %g |", (unsigned long long)particles, w, h,
           bench_smoothing_name(settings->smoothing), settings->iterations, settings->smooth_scale);
    print_ms(upload_ms);
    for (int s = FC_STAGE_DEPTH; s <= FC_STAGE_ENCODE; s++)
        print_ms(row->stage[s]);
    print_ms(gpu);
    print_ms(row->wall);
    printf(" %.2f |", 1000.0f / row->wall);
    bench_memory_print_cell(memory, pipe);
    printf("\n");
    fflush(stdout);
}

/* fluidcast's defaults but for the quantities the benchmark varies. */
static void config_settings(fc_smoothing method, uint32_t iterations, float smooth_scale, float radius,
                            const bench_options *o, fc_settings *settings)
{
    fc_settings_default(settings);
    settings->radius = radius;
    settings->filter_radius = o->filter_radius;
    settings->smoothing = method;
    settings->iterations =
        iterations == BENCH_DEFAULT_ITERATIONS ? fc_smoothing_default_iterations(method) : iterations;
    settings->smooth_scale = smooth_scale;
    settings->kernel = o->kernel;
    settings->shadow = o->shadow;
    if (o->thickness_scale > 0.0f)
        settings->thickness_scale = o->thickness_scale;
}

/* The rows of one image size: every smoothing method x iteration count x
 * smoothing resolution; "none" does not smooth, so it gets one row. */
static fc_code bench_size(fc_pipeline *pipe, const bench_options *o, const bench_memory *memory,
                          const fc_frame *frame, uint32_t w, uint32_t h, float radius, float upload_ms, fc_error *err)
{
    fc_camera cam;
    bench_scene_drop_camera(w, h, &cam);
    float sprite_px[3];
    bench_sprite_diameters(frame, &cam, radius, sprite_px);
    for (int mi = 0; mi < o->n_smoothings; mi++) {
        const fc_smoothing method = o->smoothings[mi];
        const int smooths = method != FC_SMOOTHING_NONE;
        for (int ii = 0; ii < (smooths ? o->n_iterations : 1); ii++)
            for (int ri = 0; ri < (smooths ? o->n_smooth_scales : 1); ri++) {
                fc_settings settings;
                config_settings(method, smooths ? o->iterations[ii] : 0, smooths ? o->smooth_scales[ri] : 1.0f,
                                radius, o, &settings);
                bench_row row;
                fc_code rc = bench_config(pipe, o, w, h, &settings, &row, err);
                if (rc != FC_OK)
                    return rc;
                print_row(frame->count, w, h, &settings, upload_ms, &row, memory, pipe);
                if (o->profile)
                    rc = bench_profile_config(pipe, o->frames, &cam, &settings, frame->count, sprite_px, err);
                if (o->profile && rc == FC_OK)
                    bench_memory_print_split(pipe);
                if (rc != FC_OK)
                    return rc;
            }
    }
    return FC_OK;
}

static fc_code bench_particles(fc_pipeline *pipe, const bench_options *o, const bench_memory *memory,
                               uint64_t particles, fc_error *err)
{
    fc_frame frame;
    float spacing;
    fc_code rc = bench_scene_drop(particles, &frame, &spacing, err);
    if (rc != FC_OK)
        return rc;
    float radius = BENCH_SCENE_RADIUS_PER_SPACING * spacing;
    if (o->kernel == FC_KERNEL_ANISOTROPIC)
        rc = bench_profile_anisotropy(pipe, &frame, radius, o->frames, err);
    float upload_ms = -1.0f;
    if (rc == FC_OK)
        rc = fc_pipeline_upload(pipe, &frame, &upload_ms, err);
    for (int si = 0; rc == FC_OK && si < o->n_sizes; si++)
        rc = bench_size(pipe, o, memory, &frame, o->sizes[si][0], o->sizes[si][1], radius, upload_ms, err);
    fc_frame_free(&frame);
    return rc;
}

static fc_code run_benchmark(const bench_options *o, fc_error *err)
{
    fc_gl_context *ctx = NULL;
    fc_pipeline *pipe = NULL;
    fc_code rc = fc_gl_context_create(&o->gpu, &ctx, err);
    if (rc == FC_OK) {
        printf("GL_RENDERER: %s; GL_VERSION: %s; EGL vendor: %s\n\n", fc_gl_context_renderer(ctx),
               fc_gl_context_version(ctx), fc_gl_context_egl_vendor(ctx));
        rc = fc_pipeline_create(&(fc_pipeline_config){.shader_dir = o->shader_dir, .constants = o->constants},
                                &pipe, err);
    }
    bench_memory memory = {0};
    if (rc == FC_OK) {
        fc_pipeline_force_splat(pipe, o->splat);
        bench_memory_start(&memory);
    }
    if (rc == FC_OK)
        print_header();
    for (int pi = 0; rc == FC_OK && pi < o->n_particles; pi++)
        rc = bench_particles(pipe, o, &memory, o->particles[pi], err);
    fc_pipeline_destroy(pipe);
    fc_gl_context_destroy(ctx);
    return rc;
}

/* Writes the scene the benchmark would render, and the radius it renders it with. */
static fc_code write_scene(const bench_options *o, fc_error *err)
{
    fc_frame frame;
    float spacing;
    fc_code rc = bench_scene_drop(o->particles[0], &frame, &spacing, err);
    if (rc != FC_OK)
        return rc;
    rc = bench_write_scene_f32(&frame, o->scene_path, err);
    if (rc == FC_OK)
        printf("particles %llu spacing %.9g radius %.9g\n", (unsigned long long)frame.count, spacing,
               BENCH_SCENE_RADIUS_PER_SPACING * spacing);
    fc_frame_free(&frame);
    return rc;
}

int main(int argc, char **argv)
{
    bench_options o;
    bench_options_default(&o);
    fc_error err;
    fc_code rc = bench_options_parse(argc, argv, &o, &err);
    if (rc == FC_OK && o.action == BENCH_HELP)
        bench_options_print_usage();
    else if (rc == FC_OK && o.action == BENCH_WRITE_SCENE)
        rc = write_scene(&o, &err);
    else if (rc == FC_OK)
        rc = run_benchmark(&o, &err);
    if (rc != FC_OK) {
        fprintf(stderr, "fluidcast-bench: %s\n", err.message);
        return rc == FC_ERR_USAGE ? 2 : 1;
    }
    return 0;
}
