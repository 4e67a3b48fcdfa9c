/* fluidcast-bench — per-stage timings of the render pipeline without a socket.
 *
 * For every combination of particle count, image size and smoothing method it
 * renders a warm-up frame and then --frames measured ones, and prints one
 * markdown table row with the median GPU time of each stage (timer queries),
 * the encode time and the wall time per frame. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "egl_context.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "image_encoder.h"
#include "pipeline.h"
#include "scene.h"

#define MAX_LIST 16

typedef struct bench_options {
    fc_gpu_choice gpu;
    uint64_t particles[MAX_LIST];
    int n_particles;
    uint32_t sizes[MAX_LIST][2];
    int n_sizes;
    fc_smoothing smoothings[MAX_LIST];
    int n_smoothings;
    uint32_t iterations;
    int frames;
    fc_image_format format;   /* 0 = no encoding */
} bench_options;

static const struct { const char *name; fc_smoothing value; } smoothing_names[] = {
    {"none", FC_SMOOTHING_NONE},
    {"curvature", FC_SMOOTHING_CURVATURE},
};

static const char *smoothing_name(fc_smoothing s)
{
    for (size_t i = 0; i < sizeof smoothing_names / sizeof smoothing_names[0]; i++)
        if (smoothing_names[i].value == s)
            return smoothing_names[i].name;
    return "?";
}

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
    if (end == s || *end != '\0' || v <= 0)
        return -1;
    *out = (uint64_t)(v * (double)scale);
    return 0;
}

static int parse_lists(int argc, char **argv, bench_options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(arg, "--help")) {
            printf("usage: fluidcast-bench [--gpu auto|software|N] [--particles 16k,64k,...]\n"
                   "         [--size 1280x720,...] [--smoothing curvature,none] [--iterations N]\n"
                   "         [--frames N] [--encode png|jpeg|exr|none]\n"
                   "Prints a markdown table: median GPU ms per stage (timer queries), encode ms, wall ms.\n");
            exit(0);
        }
        if (!val) {
            fprintf(stderr, "fluidcast-bench: %s needs a value\n", arg);
            return -1;
        }
        i++;
        char buf[512];
        snprintf(buf, sizeof buf, "%s", val);
        if (!strcmp(arg, "--gpu")) {
            fc_error err;
            if (fc_gpu_choice_parse(val, &o->gpu, &err) != FC_OK) {
                fprintf(stderr, "fluidcast-bench: %s\n", err.message);
                return -1;
            }
        } else if (!strcmp(arg, "--particles")) {
            o->n_particles = 0;
            for (char *t = strtok(buf, ","); t && o->n_particles < MAX_LIST; t = strtok(NULL, ","))
                if (parse_count(t, &o->particles[o->n_particles++]) != 0) {
                    fprintf(stderr, "fluidcast-bench: bad particle count '%s'\n", t);
                    return -1;
                }
        } else if (!strcmp(arg, "--size")) {
            o->n_sizes = 0;
            for (char *t = strtok(buf, ","); t && o->n_sizes < MAX_LIST; t = strtok(NULL, ",")) {
                uint32_t *wh = o->sizes[o->n_sizes++];
                if (sscanf(t, "%ux%u", &wh[0], &wh[1]) != 2 || !wh[0] || !wh[1]) {
                    fprintf(stderr, "fluidcast-bench: bad size '%s'\n", t);
                    return -1;
                }
            }
        } else if (!strcmp(arg, "--smoothing")) {
            o->n_smoothings = 0;
            for (char *t = strtok(buf, ","); t && o->n_smoothings < MAX_LIST; t = strtok(NULL, ",")) {
                size_t k = 0, n = sizeof smoothing_names / sizeof smoothing_names[0];
                while (k < n && strcmp(smoothing_names[k].name, t))
                    k++;
                if (k == n) {
                    fprintf(stderr, "fluidcast-bench: unknown smoothing '%s'\n", t);
                    return -1;
                }
                o->smoothings[o->n_smoothings++] = smoothing_names[k].value;
            }
        } else if (!strcmp(arg, "--iterations")) {
            o->iterations = (uint32_t)strtoul(val, NULL, 10);
        } else if (!strcmp(arg, "--frames")) {
            o->frames = atoi(val);
            if (o->frames < 1 || o->frames > 10000) {
                fprintf(stderr, "fluidcast-bench: --frames must be 1..10000\n");
                return -1;
            }
        } else if (!strcmp(arg, "--encode")) {
            if (!strcmp(val, "png")) o->format = FC_FORMAT_PNG;
            else if (!strcmp(val, "jpeg")) o->format = FC_FORMAT_JPEG;
            else if (!strcmp(val, "exr")) o->format = FC_FORMAT_EXR;
            else if (!strcmp(val, "none")) o->format = 0;
            else {
                fprintf(stderr, "fluidcast-bench: unknown encoding '%s'\n", val);
                return -1;
            }
        } else {
            fprintf(stderr, "fluidcast-bench: unknown option %s (see --help)\n", arg);
            return -1;
        }
    }
    return 0;
}

typedef struct bench_row {
    float stage[FC_STAGE_COUNT];
    float wall;
} bench_row;

/* Renders one configuration: a warm-up frame, then o->frames measured frames. */
static fc_code bench_config(fc_pipeline *pipe, const bench_options *o, uint32_t w, uint32_t h,
                            const fc_settings *settings, bench_row *row, fc_error *err)
{
    fc_camera cam;
    bench_scene_drop_camera(w, h, &cam);
    fc_image img = {0};
    fc_buf encoded;
    fc_buf_init(&encoded);
    float *samples = calloc((size_t)o->frames * (FC_STAGE_COUNT + 1), sizeof *samples);
    fc_code rc = samples ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "out of memory");
    for (int f = -1; rc == FC_OK && f < o->frames; f++) {
        float stage_ms[FC_STAGE_COUNT];
        const double t0 = now_ms();
        rc = fc_pipeline_render(pipe, &cam, settings, FC_AOV_COLOR, o->format != FC_FORMAT_EXR, &img,
                                stage_ms, err);
        stage_ms[FC_STAGE_ENCODE] = -1.0f;
        if (rc == FC_OK && o->format) {
            const double e0 = now_ms();
            fc_buf_reset(&encoded);
            rc = fc_encode_image(&img, o->format, 90, &encoded, err);
            stage_ms[FC_STAGE_ENCODE] = (float)(now_ms() - e0);
        }
        if (f < 0)
            continue; /* warm-up: shader compilation, allocation */
        for (int s = 0; s < FC_STAGE_COUNT; s++)
            samples[(size_t)s * o->frames + f] = stage_ms[s];
        samples[(size_t)FC_STAGE_COUNT * o->frames + f] = (float)(now_ms() - t0);
    }
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

static fc_code run(const bench_options *o, fc_pipeline *pipe, fc_error *err)
{
    printf("| particles | size | smoothing | iter | upload | depth | thickness | smoothing | composite |"
           " readback | encode | GPU sum | wall/frame | fps |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int pi = 0; pi < o->n_particles; pi++) {
        fc_frame frame;
        float spacing;
        fc_code rc = bench_scene_drop(o->particles[pi], &frame, &spacing, err);
        if (rc != FC_OK)
            return rc;
        float upload_ms = -1.0f;
        rc = fc_pipeline_upload(pipe, &frame, &upload_ms, err);
        fc_frame_free(&frame);
        if (rc != FC_OK)
            return rc;
        for (int si = 0; si < o->n_sizes; si++)
            for (int mi = 0; mi < o->n_smoothings; mi++) {
                fc_settings settings;
                fc_settings_default(&settings);
                settings.radius = 0.9f * spacing;
                settings.smoothing = o->smoothings[mi];
                settings.iterations = o->iterations;
                bench_row row;
                rc = bench_config(pipe, o, o->sizes[si][0], o->sizes[si][1], &settings, &row, err);
                if (rc != FC_OK)
                    return rc;
                float gpu = 0.0f;
                for (int s = FC_STAGE_DEPTH; s <= FC_STAGE_READBACK; s++)
                    gpu += row.stage[s] > 0 ? row.stage[s] : 0.0f;
                printf("| %llu | %ux%u | %s | %u |", (unsigned long long)o->particles[pi], o->sizes[si][0],
                       o->sizes[si][1], smoothing_name(settings.smoothing), settings.iterations);
                print_ms(upload_ms);
                for (int s = FC_STAGE_DEPTH; s <= FC_STAGE_ENCODE; s++)
                    print_ms(row.stage[s]);
                print_ms(gpu);
                print_ms(row.wall);
                printf(" %.1f |\n", 1000.0f / row.wall);
                fflush(stdout);
            }
    }
    return FC_OK;
}

int main(int argc, char **argv)
{
    bench_options o = {
        .gpu = {FC_GPU_AUTO, 0},
        .particles = {65536}, .n_particles = 1,
        .sizes = {{1280, 720}}, .n_sizes = 1,
        .smoothings = {FC_SMOOTHING_CURVATURE}, .n_smoothings = 1,
        .iterations = 40,
        .frames = 10,
        .format = FC_FORMAT_PNG,
    };
    if (parse_lists(argc, argv, &o) != 0)
        return 2;
    fc_error err;
    fc_gl_context *ctx = NULL;
    fc_pipeline *pipe = NULL;
    fc_code rc = fc_gl_context_create(&o.gpu, &ctx, &err);
    if (rc == FC_OK) {
        printf("GL_RENDERER: %s; GL_VERSION: %s; EGL vendor: %s\n\n", fc_gl_context_renderer(ctx),
               fc_gl_context_version(ctx), fc_gl_context_egl_vendor(ctx));
        rc = fc_pipeline_create(&(fc_pipeline_config){0}, &pipe, &err);
    }
    if (rc == FC_OK)
        rc = run(&o, pipe, &err);
    fc_pipeline_destroy(pipe);
    fc_gl_context_destroy(ctx);
    if (rc != FC_OK) {
        fprintf(stderr, "fluidcast-bench: %s\n", err.message);
        return 1;
    }
    return 0;
}
