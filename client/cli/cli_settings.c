/* cli_settings.c — see cli_settings.h. */
#include "cli_settings.h"

#include <stdlib.h>

#include "fc_frame.h"

/* Spray: below this share of the median density. */
#define SPRAY_DENSITY_SHARE 0.5f
/* The median is that of an evenly spread sample of at most this many particles. */
#define DENSITY_SAMPLE_MAX 4096u

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* The median density of an evenly spread sample; 0 for an empty frame. */
static float median_density(const fc_frame *frame)
{
    uint64_t n = frame->count < DENSITY_SAMPLE_MAX ? frame->count : DENSITY_SAMPLE_MAX;
    if (n == 0)
        return 0.0f;
    float sample[DENSITY_SAMPLE_MAX];
    for (uint64_t i = 0; i < n; i++)
        sample[i] = frame->density[i * frame->count / n];
    qsort(sample, (size_t)n, sizeof sample[0], compare_floats);
    return sample[n / 2];
}

void fc_cli_complete_settings(fc_settings *s, const fc_frame *frame, bool threshold_given, fc_cli_choices *chosen)
{
    *chosen = (fc_cli_choices){0};
    if (!(s->radius > 0.0f)) {
        s->radius = fc_frame_estimate_radius(frame);
        chosen->radius = true;
    }
    if (!threshold_given && frame->density) {
        float median = median_density(frame);
        if (median > 0.0f) {
            s->density_threshold = SPRAY_DENSITY_SHARE * median;
            chosen->spray = true;
        }
    }
}
