/* e2e_stats.c — latency samples: collection, median, nearest-rank p99. */
#include "e2e_stats.h"

#include <math.h>
#include <stdlib.h>
#include <time.h>

#include "fc_error.h"

fc_code e2e_samples_add(e2e_samples *s, double ms, fc_error *err)
{
    if (s->count == s->capacity) {
        size_t capacity = s->capacity ? 2 * s->capacity : 256;
        double *grown = realloc(s->ms, capacity * sizeof *grown);
        if (!grown)
            return fc_error_set(err, FC_ERR_NOMEM, "no memory for %zu latency samples", capacity);
        s->ms = grown;
        s->capacity = capacity;
    }
    s->ms[s->count++] = ms;
    return FC_OK;
}

void e2e_samples_free(e2e_samples *s)
{
    free(s->ms);
    *s = (e2e_samples){0};
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void e2e_latency_summarize(e2e_samples *s, e2e_latency *out)
{
    *out = (e2e_latency){.count = s->count};
    if (s->count == 0)
        return;
    qsort(s->ms, s->count, sizeof s->ms[0], compare_doubles);
    size_t n = s->count;
    out->median_ms = n % 2 ? s->ms[n / 2] : 0.5 * (s->ms[n / 2 - 1] + s->ms[n / 2]);
    size_t rank = (size_t)ceil(0.99 * (double)n);
    out->p99_ms = s->ms[rank - 1];
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += s->ms[i];
    out->mean_ms = sum / (double)n;
}

double e2e_now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}
