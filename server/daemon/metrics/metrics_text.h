/* metrics_text.h — the metrics in Prometheus' text exposition format
 * (version 0.0.4): counters end in _total, durations are in seconds and sizes
 * in bytes, histograms have cumulative buckets whose +Inf equals _count. */
#ifndef FC_DAEMON_METRICS_TEXT_H
#define FC_DAEMON_METRICS_TEXT_H

#include <stddef.h>

#include "metrics/metrics.h"

#define FC_METRICS_CONTENT_TYPE "text/plain; version=0.0.4; charset=utf-8"

/* The whole exposition as one malloc'd string (*length bytes, NUL-terminated),
 * or NULL when out of memory. */
char *fc_metrics_text(fc_metrics *m, size_t *length);

#endif
