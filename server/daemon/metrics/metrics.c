/* metrics.c — the counters as C11 atomics: relaxed operations on the hot
 * paths (a counter need not be ordered against anything else), a lock only
 * for the build_info strings, which are set once. */
#include "metrics/metrics.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fc_error.h"

/* 1 ms to 30 s: from encoding a small image to a large render on llvmpipe. */
const double fc_metric_bucket_bounds[FC_METRIC_BUCKETS] = {0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1,
                                                           0.25,  0.5,    1.0,   2.5,  5.0,   10.0, 30.0};

typedef struct histogram {
    atomic_uint_fast64_t buckets[FC_METRIC_BUCKETS + 1];   /* the last: +Inf */
    atomic_uint_fast64_t sum_ns;                           /* nanoseconds: an integer adds atomically */
} histogram;

struct fc_metrics {
    atomic_uint_fast64_t counters[FC_METRIC_COUNTER_COUNT];
    atomic_int_fast64_t gauges[FC_METRIC_GAUGE_COUNT];
    histogram histograms[FC_METRIC_HISTOGRAM_COUNT];
    atomic_int phase;
    double start_time;
    pthread_mutex_t lock;   /* guards info */
    fc_metrics_build_info info;
};

fc_code fc_metrics_create(fc_metrics **out, fc_error *err)
{
    fc_metrics *m = calloc(1, sizeof *m);
    if (!m)
        return fc_error_set(err, FC_ERR_NOMEM, "metrics: out of memory");
    for (int i = 0; i < FC_METRIC_COUNTER_COUNT; i++)
        atomic_init(&m->counters[i], 0);
    for (int i = 0; i < FC_METRIC_GAUGE_COUNT; i++)
        atomic_init(&m->gauges[i], 0);
    atomic_init(&m->gauges[FC_METRIC_GPU_MEMORY_TOTAL], -1);
    atomic_init(&m->gauges[FC_METRIC_GPU_MEMORY_AVAILABLE], -1);
    for (int h = 0; h < FC_METRIC_HISTOGRAM_COUNT; h++) {
        for (int b = 0; b <= FC_METRIC_BUCKETS; b++)
            atomic_init(&m->histograms[h].buckets[b], 0);
        atomic_init(&m->histograms[h].sum_ns, 0);
    }
    atomic_init(&m->phase, FC_PHASE_STARTING);
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    m->start_time = (double)now.tv_sec + now.tv_nsec / 1e9;
    pthread_mutex_init(&m->lock, NULL);
    *out = m;
    return FC_OK;
}

void fc_metrics_destroy(fc_metrics *m)
{
    if (!m)
        return;
    pthread_mutex_destroy(&m->lock);
    free(m);
}

void fc_metrics_add(fc_metrics *m, fc_metric_counter counter, uint64_t n)
{
    if (m)
        atomic_fetch_add_explicit(&m->counters[counter], n, memory_order_relaxed);
}

void fc_metrics_set(fc_metrics *m, fc_metric_gauge gauge, int64_t value)
{
    if (m)
        atomic_store_explicit(&m->gauges[gauge], value, memory_order_relaxed);
}

void fc_metrics_observe(fc_metrics *m, fc_metric_histogram which, double seconds)
{
    if (!m)
        return;
    if (!(seconds >= 0.0))   /* negative or NaN: not measured */
        return;
    int bucket = 0;
    while (bucket < FC_METRIC_BUCKETS && seconds > fc_metric_bucket_bounds[bucket])
        bucket++;
    histogram *h = &m->histograms[which];
    atomic_fetch_add_explicit(&h->buckets[bucket], 1, memory_order_relaxed);
    atomic_fetch_add_explicit(&h->sum_ns, (uint64_t)(seconds * 1e9 + 0.5), memory_order_relaxed);
}

void fc_metrics_set_phase(fc_metrics *m, fc_metric_phase phase)
{
    if (m)
        atomic_store_explicit(&m->phase, (int)phase, memory_order_release);
}

void fc_metrics_set_build_info(fc_metrics *m, const char *version, const char *renderer, const char *device)
{
    if (!m)
        return;
    pthread_mutex_lock(&m->lock);
    snprintf(m->info.version, sizeof m->info.version, "%s", version ? version : "");
    snprintf(m->info.renderer, sizeof m->info.renderer, "%s", renderer ? renderer : "");
    snprintf(m->info.device, sizeof m->info.device, "%s", device ? device : "");
    pthread_mutex_unlock(&m->lock);
}

uint64_t fc_metrics_counter(fc_metrics *m, fc_metric_counter counter)
{
    return atomic_load_explicit(&m->counters[counter], memory_order_relaxed);
}

int64_t fc_metrics_gauge(fc_metrics *m, fc_metric_gauge gauge)
{
    return atomic_load_explicit(&m->gauges[gauge], memory_order_relaxed);
}

fc_metric_phase fc_metrics_phase(fc_metrics *m)
{
    return (fc_metric_phase)atomic_load_explicit(&m->phase, memory_order_acquire);
}

void fc_metrics_histogram(fc_metrics *m, fc_metric_histogram which, fc_metrics_histogram_snapshot *out)
{
    histogram *h = &m->histograms[which];
    for (int b = 0; b <= FC_METRIC_BUCKETS; b++)
        out->buckets[b] = atomic_load_explicit(&h->buckets[b], memory_order_relaxed);
    out->sum_seconds = (double)atomic_load_explicit(&h->sum_ns, memory_order_relaxed) / 1e9;
}

void fc_metrics_build_info_get(fc_metrics *m, fc_metrics_build_info *out)
{
    pthread_mutex_lock(&m->lock);
    *out = m->info;
    pthread_mutex_unlock(&m->lock);
}

double fc_metrics_start_time(fc_metrics *m)
{
    return m->start_time;
}
