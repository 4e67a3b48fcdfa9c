/* up_axis.c — see up_axis.h. */
#include "up_axis.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "spread_sample.h"

/* End slabs this many spacings thick hold the first layer or two of a floor
 * whatever the jitter, but only the very tip of a crest or jet. */
#define SLAB_SPACINGS 1.5
/* One end slab: how many particles, and their extents across the axis. */
typedef struct end_slab {
    uint32_t count;
    float lo[3], hi[3];
} end_slab;

static void add_to_slab(end_slab *s, const float *p)
{
    s->count++;
    for (int k = 0; k < 3; k++) {
        s->lo[k] = fminf(s->lo[k], p[k]);
        s->hi[k] = fmaxf(s->hi[k], p[k]);
    }
}

/* Fills the six end slabs (ends[axis][0 low, 1 high]) of the given thickness. */
static void collect_ends(const fc_frame *sample, const float lo[3], const float hi[3], double slab,
                         end_slab ends[3][2])
{
    for (int k = 0; k < 3; k++)
        for (int e = 0; e < 2; e++)
            ends[k][e] = (end_slab){.count = 0, .lo = {FLT_MAX, FLT_MAX, FLT_MAX}, .hi = {-FLT_MAX, -FLT_MAX, -FLT_MAX}};
    for (uint64_t i = 0; i < sample->count; i++) {
        const float *p = sample->positions + 3 * i;
        for (int k = 0; k < 3; k++) {
            if ((double)p[k] <= (double)lo[k] + slab)
                add_to_slab(&ends[k][0], p);
            if ((double)p[k] >= (double)hi[k] - slab)
                add_to_slab(&ends[k][1], p);
        }
    }
}

/* The smaller of the slab's extents along the other two axes, relative to the
 * fluid's; 1 along an axis where the fluid is flat. */
static float relative_span(const end_slab *s, int axis, const float lo[3], const float hi[3])
{
    float span = 1.0f;
    for (int j = 0; j < 3; j++)
        if (j != axis && hi[j] > lo[j])
            span = fminf(span, (s->hi[j] - s->lo[j]) / (hi[j] - lo[j]));
    return span;
}

/* Counts, spans and contrast of each axis's ends. An axis whose extent cannot
 * hold two separate slabs gets contrast 0: its counts say nothing about which
 * end is which. */
static void measure_ends(const fc_frame *sample, double slab, fc_up_guess *g)
{
    float lo[3], hi[3];
    fc_frame_bounds(sample, lo, hi);
    end_slab ends[3][2];
    collect_ends(sample, lo, hi, slab, ends);
    for (int k = 0; k < 3; k++) {
        for (int e = 0; e < 2; e++) {
            g->end_count[k][e] = ends[k][e].count;
            g->end_span[k][e] = relative_span(&ends[k][e], k, lo, hi);
        }
        uint32_t larger = ends[k][0].count > ends[k][1].count ? ends[k][0].count : ends[k][1].count;
        bool separate = (double)lo[k] + slab < (double)hi[k] - slab;
        g->contrast[k] = separate && larger ? (float)((double)ends[k][0].count - ends[k][1].count) / (float)larger
                                            : 0.0f;
    }
}

static int dense_end(const fc_up_guess *g, int k)
{
    return g->contrast[k] > 0 ? 0 : 1;
}

/* Contrast weighted by the size of the axis's dense end relative to the
 * largest dense end; 0 where the dense end does not span the fluid. */
static void score_axes(const fc_up_guess *g, float score[3])
{
    uint32_t largest = 1;
    for (int k = 0; k < 3; k++)
        if (g->end_count[k][dense_end(g, k)] > largest)
            largest = g->end_count[k][dense_end(g, k)];
    for (int k = 0; k < 3; k++) {
        int e = dense_end(g, k);
        bool floor = g->end_span[k][e] >= FC_UP_MIN_SPAN;
        score[k] = floor ? fabsf(g->contrast[k]) * (float)g->end_count[k][e] / (float)largest : 0.0f;
    }
}

/* The axis to call the gravity axis, or -1 when none stands out. Near-ties
 * are settled by the order z, y, x. */
static int pick_axis(const fc_up_guess *g)
{
    float score[3], best = 0.0f;
    score_axes(g, score);
    for (int k = 0; k < 3; k++)
        best = fmaxf(best, score[k]);
    int axis = 2;
    while (score[axis] < best - FC_UP_TIE)
        axis--;
    if (score[axis] <= 0.0f || fabsf(g->contrast[axis]) < FC_UP_MIN_CONTRAST ||
        g->end_count[axis][dense_end(g, axis)] < FC_UP_MIN_FLOOR)
        return -1;
    return axis;
}

static void analyse(const fc_frame *sample, fc_up_guess *g)
{
    double spacing = fc_sample_spacing(sample);
    if (!(spacing > 0.0))
        return;
    g->slab = (float)(SLAB_SPACINGS * spacing);
    measure_ends(sample, g->slab, g);
    int axis = pick_axis(g);
    if (axis >= 0) {
        g->axis = axis;
        g->sign = g->contrast[axis] > 0 ? 1 : -1;
        g->from_particles = true;
    }
}

fc_code fc_up_axis_guess(const fc_frame *frame, fc_up_guess *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    out->axis = 2;
    out->sign = 1;
    if (frame->count < 2)
        return FC_OK;
    uint64_t m = frame->count < FC_UP_SAMPLE_MAX ? frame->count : FC_UP_SAMPLE_MAX;
    out->sampled = m;
    if (m == frame->count) {
        analyse(frame, out);
        return FC_OK;
    }
    float *positions = malloc(m * 3 * sizeof *positions);
    if (!positions)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %llu-particle sample to guess the up axis",
                            (unsigned long long)m);
    fc_spread_sample(frame, positions, m);
    fc_frame sample = {.count = m, .positions = positions};
    analyse(&sample, out);
    free(positions);
    return FC_OK;
}

void fc_up_axis_vector(const fc_up_guess *guess, float up[3])
{
    for (int k = 0; k < 3; k++)
        up[k] = k == guess->axis ? (float)guess->sign : 0.0f;
}

const char *fc_up_axis_name(int axis, int sign)
{
    static const char *const names[3][2] = {{"-x", "+x"}, {"-y", "+y"}, {"-z", "+z"}};
    return names[axis][sign > 0];
}
