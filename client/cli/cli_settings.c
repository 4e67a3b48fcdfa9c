/* cli_settings.c — see cli_settings.h. */
#include "cli_settings.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fc_frame.h"

/* The colour range's percentiles, over an evenly spread sample of at most this many particles. */
#define COLOR_SAMPLE_MAX 65536u
#define COLOR_LOW_PERCENTILE 0.02
#define COLOR_HIGH_PERCENTILE 0.98

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Particle i's value of the attribute `by`. */
static float attribute_value(const fc_frame *frame, fc_color_by by, uint64_t i)
{
    if (by == FC_COLOR_BY_DENSITY)
        return frame->density[i];
    const float *v = frame->velocity + 3 * i;
    return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* The value at fraction q of the sorted sample. */
static float percentile(const float *sorted, uint64_t n, double q)
{
    return sorted[(uint64_t)(q * (double)(n - 1) + 0.5)];
}

void fc_cli_complete_color_range(fc_settings *s, const fc_frame *frame, bool range_given, fc_cli_choices *chosen)
{
    bool has = s->color_by == FC_COLOR_BY_SPEED ? frame->velocity != NULL
               : s->color_by == FC_COLOR_BY_DENSITY ? frame->density != NULL
                                                     : false;
    /* Without the attribute the server's refusal names what is missing. */
    if (range_given || !has || frame->count == 0)
        return;
    uint64_t n = frame->count < COLOR_SAMPLE_MAX ? frame->count : COLOR_SAMPLE_MAX;
    float *sample = malloc((size_t)n * sizeof *sample);
    if (!sample)
        return;
    for (uint64_t i = 0; i < n; i++)
        sample[i] = attribute_value(frame, s->color_by, i * frame->count / n);
    qsort(sample, (size_t)n, sizeof sample[0], compare_floats);
    float lo = percentile(sample, n, COLOR_LOW_PERCENTILE), hi = percentile(sample, n, COLOR_HIGH_PERCENTILE);
    free(sample);
    if (!(isfinite(lo) && isfinite(hi)))
        return;
    s->color_range[0] = lo;
    s->color_range[1] = hi > lo ? hi : lo + 1.0f;
    chosen->color_range = true;
}

void fc_cli_complete_settings(fc_settings *s, const fc_frame *frame, fc_cli_choices *chosen)
{
    *chosen = (fc_cli_choices){0};
    switch (fc_radius_source_of(s, frame->radius != NULL)) {
    case FC_RADIUS_PER_PARTICLE: {
        s->radius = 0.0f;
        chosen->per_particle_radius = true;
        fc_error ignored;
        if (fc_frame_median_radius(frame, &chosen->median_radius, &ignored) != FC_OK)
            chosen->median_radius = 0.0f;
        break;
    }
    case FC_RADIUS_ESTIMATED:
        s->radius = fc_frame_estimate_radius(frame);
        chosen->radius = true;
        break;
    case FC_RADIUS_FROM_SETTINGS: break;
    }
}

void fc_cli_print_color_range(const fc_settings *s)
{
    printf("color range: %s %.9g:%.9g (2nd-98th percentile of the frame; --range %.9g:%.9g to fix it)\n",
           s->color_by == FC_COLOR_BY_SPEED ? "speed" : "density", (double)s->color_range[0],
           (double)s->color_range[1], (double)s->color_range[0], (double)s->color_range[1]);
}

void fc_cli_print_radius(const fc_settings *s, const fc_cli_choices *chosen, const char *estimated_from)
{
    if (chosen->per_particle_radius)
        printf("radius: per-particle radii from the file (median %g; --radius R renders every particle at R)\n",
               (double)chosen->median_radius);
    else if (chosen->radius)
        printf("radius %g (estimated from %s)\n", (double)s->radius, estimated_from);
}
