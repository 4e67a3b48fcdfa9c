/* spread_sample.c — see spread_sample.h. */
#include "spread_sample.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The spacing is the median nearest-neighbour distance of this many sampled
 * particles, found by brute force among the whole sample: a couple of million
 * distances, about a millisecond, where fc_frame_estimate_radius's exact
 * search would take tens (it is made for the radius, not for this). */
#define SPACING_QUERIES 128u

static uint64_t gcd64(uint64_t a, uint64_t b)
{
    while (b) {
        uint64_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

void fc_spread_sample(const fc_frame *frame, float *xyz, uint64_t m)
{
    uint64_t n = frame->count;
    uint64_t step = (uint64_t)((double)n * 0.6180339887) | 1u;
    while (gcd64(step, n) != 1)
        step += 2;
    uint64_t index = 0;
    for (uint64_t i = 0; i < m; i++) {
        memcpy(xyz + 3 * i, frame->positions + 3 * index, 3 * sizeof *xyz);
        index = (index + step) % n;
    }
}

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Squared distance from particle q to its nearest neighbour at a different
 * position in the sample; FLT_MAX when every particle sits on q. */
static float nearest_sq(const fc_frame *sample, uint64_t q)
{
    const float *p = sample->positions + 3 * q;
    float best = FLT_MAX;
    for (uint64_t j = 0; j < sample->count; j++) {
        const float *o = sample->positions + 3 * j;
        float dx = o[0] - p[0], dy = o[1] - p[1], dz = o[2] - p[2];
        float d = dx * dx + dy * dy + dz * dz;
        if (d > 0.0f && d < best)
            best = d;
    }
    return best;
}

double fc_sample_spacing(const fc_frame *sample)
{
    float distances[SPACING_QUERIES];
    uint32_t found = 0;
    uint64_t queries = sample->count < SPACING_QUERIES ? sample->count : SPACING_QUERIES;
    for (uint64_t i = 0; i < queries; i++) {
        float d = nearest_sq(sample, i * (sample->count / queries));
        if (d < FLT_MAX)
            distances[found++] = sqrtf(d);
    }
    if (found == 0)
        return 0.0;
    qsort(distances, found, sizeof distances[0], compare_floats);
    return distances[found / 2];
}
