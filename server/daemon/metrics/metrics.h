/* metrics.h — the daemon's counters, gauges and histograms, and whether it is
 * ready: updated by the event loop's thread (and any other) with one relaxed
 * atomic operation each, read by the metrics endpoint's thread
 * (metrics_text.h writes them in Prometheus' text format). Depends on nothing
 * else of the daemon: every layer may count here. */
#ifndef FC_DAEMON_METRICS_H
#define FC_DAEMON_METRICS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef enum fc_metric_counter {
    FC_METRIC_CONNECTIONS_ACCEPTED = 0,
    FC_METRIC_MESSAGES_RECEIVED,
    FC_METRIC_BYTES_RECEIVED,
    FC_METRIC_BYTES_SENT,
    FC_METRIC_FRAMES_RENDERED,         /* images rendered and encoded: IMAGE and STREAM_IMAGE */
    FC_METRIC_DROPPED_VIEWER_BUSY,     /* frames a viewer skipped: latest wins (PROTOCOL.md 10.1) */
    FC_METRIC_DROPPED_RENDER_FAILED,   /* renders that failed on the GPU or in the encoder */
    FC_METRIC_DROPPED_CLIENT_GONE,     /* images finished for a connection that had closed */
    FC_METRIC_LIMIT_REJECTIONS,        /* ERROR LIMIT replies: a limit of the server refused a request */
    FC_METRIC_TLS_HANDSHAKES,          /* TLS handshakes completed */
    FC_METRIC_TLS_HANDSHAKE_FAILURES,  /* TLS handshakes failed, and clients without TLS on a TLS port */
    FC_METRIC_TLS_HANDSHAKE_TIMEOUTS,  /* TLS handshakes dropped as stalled (--tls-handshake-timeout-ms) */
    FC_METRIC_COUNTER_COUNT
} fc_metric_counter;

typedef enum fc_metric_gauge {
    FC_METRIC_CONNECTIONS = 0,         /* client connections open */
    FC_METRIC_SESSIONS,                /* named sessions */
    FC_METRIC_GPU_MEMORY_TOTAL,        /* bytes; negative: unknown (the driver does not say) */
    FC_METRIC_GPU_MEMORY_AVAILABLE,
    FC_METRIC_GAUGE_COUNT
} fc_metric_gauge;

typedef enum fc_metric_histogram {
    FC_METRIC_RENDER_SECONDS = 0,      /* GPU work of one image: upload through readback */
    FC_METRIC_ENCODE_SECONDS,          /* encoding one image (PNG, JPEG, EXR, ...) */
    FC_METRIC_HISTOGRAM_COUNT
} fc_metric_histogram;

/* Upper bounds of the histograms' buckets, seconds; +Inf follows the last. */
#define FC_METRIC_BUCKETS 14
extern const double fc_metric_bucket_bounds[FC_METRIC_BUCKETS];

/* Where the daemon is in its life, for /readyz. */
typedef enum fc_metric_phase {
    FC_PHASE_STARTING = 0,             /* no GL context or no listener yet */
    FC_PHASE_SERVING,
    FC_PHASE_DRAINING                  /* stop signal received: answering what is in flight */
} fc_metric_phase;

typedef struct fc_metrics fc_metrics;

/* Everything zero, the GPU memory unknown, the phase STARTING. */
fc_code fc_metrics_create(fc_metrics **out, fc_error *err);
void fc_metrics_destroy(fc_metrics *m);

/* Each of these accepts m == NULL (nothing counted), so code paths that run
 * without a daemon (tests of one layer) need no metrics. */
void fc_metrics_add(fc_metrics *m, fc_metric_counter counter, uint64_t n);
void fc_metrics_set(fc_metrics *m, fc_metric_gauge gauge, int64_t value);
void fc_metrics_observe(fc_metrics *m, fc_metric_histogram histogram, double seconds);
void fc_metrics_set_phase(fc_metrics *m, fc_metric_phase phase);

/* What build_info reports; copied, set once the GL context exists. */
void fc_metrics_set_build_info(fc_metrics *m, const char *version, const char *renderer, const char *device);

/* Readers (any thread). */
uint64_t fc_metrics_counter(fc_metrics *m, fc_metric_counter counter);
int64_t fc_metrics_gauge(fc_metrics *m, fc_metric_gauge gauge);
fc_metric_phase fc_metrics_phase(fc_metrics *m);

/* One histogram as read at one moment: per-bucket (not cumulative) counts,
 * the last being +Inf, and the sum of the observations. */
typedef struct fc_metrics_histogram_snapshot {
    uint64_t buckets[FC_METRIC_BUCKETS + 1];
    double sum_seconds;
} fc_metrics_histogram_snapshot;
void fc_metrics_histogram(fc_metrics *m, fc_metric_histogram histogram, fc_metrics_histogram_snapshot *out);

/* build_info's labels, copied under the lock that guards them. */
typedef struct fc_metrics_build_info {
    char version[64];
    char renderer[128];
    char device[128];
} fc_metrics_build_info;
void fc_metrics_build_info_get(fc_metrics *m, fc_metrics_build_info *out);

/* Seconds since the Unix epoch when the metrics were created (the process start). */
double fc_metrics_start_time(fc_metrics *m);

#endif
