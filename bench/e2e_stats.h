/* e2e_stats.h — latency samples and their summary for fluidcast-e2e-bench. */
#ifndef FC_E2E_STATS_H
#define FC_E2E_STATS_H

#include <stddef.h>

#include "fluidcast_types.h"

/* A growing list of latencies in milliseconds. Zero-initialise; e2e_samples_free releases. */
typedef struct e2e_samples {
    double *ms;
    size_t count;
    size_t capacity;
} e2e_samples;

fc_code e2e_samples_add(e2e_samples *s, double ms, fc_error *err);
void e2e_samples_free(e2e_samples *s);

typedef struct e2e_latency {
    size_t count;
    double median_ms;     /* mean of the two middle samples for an even count */
    double p99_ms;        /* nearest rank: the ceil(0.99 n)-th smallest, so the maximum for n <= 100 */
    double mean_ms;
} e2e_latency;

/* Sorts the samples and summarises them; all zero for no samples. */
void e2e_latency_summarize(e2e_samples *s, e2e_latency *out);

/* CLOCK_MONOTONIC in milliseconds. */
double e2e_now_ms(void);

#endif
