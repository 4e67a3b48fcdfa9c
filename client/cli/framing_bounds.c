/* framing_bounds.c — see framing_bounds.h. */
#include "framing_bounds.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "fc_error.h"
#include "spread_sample.h"

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* axis[i] = coordinate k of the sample's i-th particle, sorted. */
static void sorted_axis(const fc_frame *sample, int k, float *axis)
{
    for (uint64_t i = 0; i < sample->count; i++)
        axis[i] = sample->positions[3 * i + (uint64_t)k];
    qsort(axis, sample->count, sizeof *axis, compare_floats);
}

/* The cuts along one sorted axis: from the tail percentiles outwards while no
 * neighbours are more than `gap` apart, then a gap's width further. Even where
 * that reaches the sample's last particle, unsampled ones beyond are cut: they
 * are more than a gap away from every sampled one. */
static void axis_cuts(const float *axis, uint64_t m, uint64_t tail, double gap, double *lo, double *hi)
{
    uint64_t j = m - 1 - tail;
    while (j + 1 < m && (double)axis[j + 1] - axis[j] <= gap)
        j++;
    *hi = (double)axis[j] + gap;
    j = tail;
    while (j > 0 && (double)axis[j] - axis[j - 1] <= gap)
        j--;
    *lo = (double)axis[j] - gap;
}

/* The cuts of all three axes from the sample; sorted: 3 x sample->count floats. */
static void choose_cuts(const fc_frame *sample, float *sorted, double lo[3], double hi[3])
{
    uint64_t m = sample->count;
    /* Below 1 / FC_FRAMING_TAIL particles the tail is empty: nothing to leave out. */
    uint64_t tail = (uint64_t)(FC_FRAMING_TAIL * (double)m);
    double size = 0.0;
    for (int k = 0; k < 3; k++) {
        float *axis = sorted + (uint64_t)k * m;
        sorted_axis(sample, k, axis);
        size = fmax(size, (double)axis[m - 1 - tail] - axis[tail]);
    }
    double gap = fmax(FC_FRAMING_GAP * size, FC_FRAMING_GAP_SPACINGS * fc_sample_spacing(sample));
    for (int k = 0; k < 3; k++)
        axis_cuts(sorted + (uint64_t)k * m, m, tail, gap, &lo[k], &hi[k]);
}

static bool inside(const float *p, const double lo[3], const double hi[3])
{
    for (int k = 0; k < 3; k++)
        if (!((double)p[k] >= lo[k] && (double)p[k] <= hi[k]))
            return false;
    return true;
}

/* The box of every particle inside the cuts, and how many are not. */
static void box_within(const fc_frame *frame, const double lo[3], const double hi[3], fc_framing_box *out)
{
    bool any = false;
    for (uint64_t i = 0; i < frame->count; i++) {
        const float *p = frame->positions + 3 * i;
        if (!inside(p, lo, hi)) {
            out->left_out++;
            continue;
        }
        for (int k = 0; k < 3; k++) {
            out->lo[k] = any && out->lo[k] < p[k] ? out->lo[k] : p[k];
            out->hi[k] = any && out->hi[k] > p[k] ? out->hi[k] : p[k];
        }
        any = true;
    }
}

fc_code fc_framing_box_of(const fc_frame *frame, fc_framing_box *out, fc_error *err)
{
    *out = (fc_framing_box){0};
    if (frame->count == 0)
        return FC_OK;   /* nothing to frame: the empty box at the origin */
    uint64_t m = frame->count < FC_FRAMING_SAMPLE_MAX ? frame->count : FC_FRAMING_SAMPLE_MAX;
    float *buffer = malloc(6 * m * sizeof *buffer);   /* the sample's xyz, then its three sorted axes */
    if (!buffer)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %llu-particle sample to frame the fluid",
                            (unsigned long long)m);
    fc_spread_sample(frame, buffer, m);
    const fc_frame sample = {.count = m, .positions = buffer};
    double lo[3], hi[3];
    choose_cuts(&sample, buffer + 3 * m, lo, hi);
    free(buffer);
    out->sampled = m;
    /* Every sampled particle between the tail percentiles of all three axes is
     * inside the cuts, and at most 6 tails (3%) of the sample are outside
     * those: the box holds at least one particle. */
    box_within(frame, lo, hi, out);
    return FC_OK;
}

void fc_framing_box_union(fc_framing_box *into, const fc_framing_box *box)
{
    for (int k = 0; k < 3; k++) {
        into->lo[k] = box->lo[k] < into->lo[k] ? box->lo[k] : into->lo[k];
        into->hi[k] = box->hi[k] > into->hi[k] ? box->hi[k] : into->hi[k];
    }
    into->left_out = box->left_out > into->left_out ? box->left_out : into->left_out;
    into->sampled = box->sampled > into->sampled ? box->sampled : into->sampled;
}
