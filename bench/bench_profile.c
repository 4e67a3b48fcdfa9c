/* bench_profile.c — per-pass profile tables of fluidcast-bench. */
#include "bench_profile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_options.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "pipeline_internal.h"

static int compare_float(const void *a, const void *b)
{
    const float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

void bench_sprite_diameters(const fc_frame *frame, const fc_camera *cam, float radius, float out[3])
{
    float forward[3], length = 0.0f;
    for (int i = 0; i < 3; i++) {
        forward[i] = cam->target[i] - cam->eye[i];
        length += forward[i] * forward[i];
    }
    length = sqrtf(length);
    /* Pixels per world unit at unit depth, vertically. */
    const float focal_px = 0.5f * (float)cam->height / tanf(cam->fov_y_deg * 3.14159265f / 360.0f);
    float *d = malloc(frame->count * sizeof *d);
    uint64_t n = 0;
    for (uint64_t k = 0; d && k < frame->count; k++) {
        const float *p = frame->positions + 3 * k;
        float depth = 0.0f;
        for (int i = 0; i < 3; i++)
            depth += (p[i] - cam->eye[i]) * forward[i] / length;
        if (depth > radius)
            d[n++] = 2.0f * radius * focal_px / depth;
    }
    out[0] = out[1] = out[2] = 0.0f;
    if (n > 0) {
        qsort(d, n, sizeof *d, compare_float);
        out[0] = d[0];
        out[1] = d[n / 2];
        out[2] = d[n - 1];
    }
    free(d);
}

/* The passes of every profiled frame, by name in first-seen order. */
typedef struct pass_series {
    const char *name;
    float *ms;
    float *cpu_ms;
    float *fragments;
    int n;
} pass_series;

#define MAX_PASSES 32

static pass_series *series_of(pass_series *all, int *count, const char *name, int frames)
{
    for (int i = 0; i < *count; i++)
        if (!strcmp(all[i].name, name))
            return &all[i];
    if (*count == MAX_PASSES)
        return NULL;
    pass_series *s = &all[(*count)++];
    *s = (pass_series){.name = name, .ms = calloc((size_t)frames, sizeof(float)),
                       .cpu_ms = calloc((size_t)frames, sizeof(float)),
                       .fragments = calloc((size_t)frames, sizeof(float))};
    return s->ms && s->cpu_ms && s->fragments ? s : NULL;
}

/* Sums the samples of one frame per pass name (a pass may run several times). */
static fc_code collect(const fc_pass_sample *samples, int n, int frame, int frames, pass_series *all, int *count,
                       fc_error *err)
{
    for (int i = 0; i < n; i++) {
        pass_series *s = series_of(all, count, samples[i].name, frames);
        if (!s)
            return fc_error_set(err, FC_ERR_NOMEM, "out of memory (or too many passes) for the profile");
        s->ms[frame] += (float)samples[i].ms;
        s->cpu_ms[frame] += (float)samples[i].cpu_ms;
        s->fragments[frame] += (float)samples[i].fragments;
        s->n = frame + 1;
    }
    return FC_OK;
}

static float median_of(float *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_float);
    return n % 2 ? v[n / 2] : 0.5f * (v[n / 2 - 1] + v[n / 2]);
}

static void print_table(pass_series *all, int count, int frames, uint64_t particles, const fc_camera *cam,
                        const fc_settings *settings, const float sprite_px[3], fc_splat_method splat)
{
    printf("\nprofile: %llu particles, %ux%u, smoothing %s x%u at %g, sprite diameter px min %.1f median %.1f "
           "max %.1f, %s splat\n\n",
           (unsigned long long)particles, cam->width, cam->height, bench_smoothing_name(settings->smoothing),
           settings->iterations,
           settings->smooth_scale, sprite_px[0], sprite_px[1], sprite_px[2],
           splat == FC_SPLAT_COMPUTE ? "compute" : "fragment");
    printf("| pass | ms | CPU ms | fragments | fragments / pixel | fragments / particle |\n"
           "|---|---|---|---|---|---|\n");
    float total = 0.0f, total_cpu = 0.0f;
    const float pixels = (float)cam->width * (float)cam->height;
    for (int i = 0; i < count; i++) {
        float ms = median_of(all[i].ms, frames), cpu_ms = median_of(all[i].cpu_ms, frames);
        float fragments = median_of(all[i].fragments, frames);
        total += ms;
        total_cpu += cpu_ms;
        printf("| %s | %.2f | %.2f | %.0f | %.2f | %.1f |\n", all[i].name, ms, cpu_ms, fragments, fragments / pixels,
               fragments / (float)particles);
    }
    printf("| sum | %.2f | %.2f | | | |\n\n", total, total_cpu);
    fflush(stdout);
}

fc_code bench_profile_config(fc_pipeline *pipe, int frames, const fc_camera *cam, const fc_settings *settings,
                             uint64_t particles, const float sprite_px[3], fc_error *err)
{
    pass_series all[MAX_PASSES];
    int count = 0;
    fc_image img = {0};
    fc_pipeline_set_profiling(pipe, 1);
    fc_code rc = FC_OK;
    for (int f = 0; rc == FC_OK && f < frames; f++) {
        rc = fc_pipeline_render(pipe, cam, settings, FC_AOV_COLOR, 1, &img, NULL, err);
        const fc_pass_sample *samples = NULL;
        int n = fc_pipeline_pass_profile(pipe, &samples);
        if (rc == FC_OK)
            rc = collect(samples, n, f, frames, all, &count, err);
    }
    fc_pipeline_set_profiling(pipe, 0);
    if (rc == FC_OK)
        print_table(all, count, frames, particles, cam, settings, sprite_px, fc_pipeline_last_splat(pipe));
    for (int i = 0; i < count; i++) {
        free(all[i].ms);
        free(all[i].cpu_ms);
        free(all[i].fragments);
    }
    fc_image_free(&img);
    return rc;
}

/* The "anisotropy" sample of the last profiled render; -1 without one. */
static float anisotropy_ms(const fc_pipeline *pipe)
{
    const fc_pass_sample *samples = NULL;
    int n = fc_pipeline_pass_profile(pipe, &samples);
    for (int i = 0; i < n; i++)
        if (!strcmp(samples[i].name, "anisotropy"))
            return (float)samples[i].ms;
    return -1.0f;
}

fc_code bench_profile_anisotropy(fc_pipeline *pipe, const fc_frame *frame, float radius, int frames,
                                 fc_error *err)
{
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = radius;
    settings.kernel = FC_KERNEL_ANISOTROPIC;
    settings.smoothing = FC_SMOOTHING_NONE;
    /* A tiny image: the render around the passes costs next to nothing. */
    const fc_camera cam = {.eye = {0.0f, -3.0f, 1.0f}, .up = {0.0f, 0.0f, 1.0f}, .fov_y_deg = 40.0f,
                           .width = 16, .height = 16};
    float *ms = calloc((size_t)frames, sizeof *ms);
    fc_code rc = ms ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "out of memory");
    fc_image img = {0};
    fc_pipeline_set_profiling(pipe, 1);
    for (int f = 0; rc == FC_OK && f < frames; f++) {
        rc = fc_pipeline_upload(pipe, frame, NULL, err);
        if (rc == FC_OK)
            rc = fc_pipeline_render(pipe, &cam, &settings, FC_AOV_DEPTH, 0, &img, NULL, err);
        ms[f] = anisotropy_ms(pipe);
    }
    fc_pipeline_set_profiling(pipe, 0);
    if (rc == FC_OK)
        printf("\nanisotropy passes: %llu particles, radius %g: %.2f ms (median of %d computations)\n\n",
               (unsigned long long)frame->count, (double)radius, median_of(ms, frames), frames);
    fflush(stdout);
    free(ms);
    fc_image_free(&img);
    return rc;
}
