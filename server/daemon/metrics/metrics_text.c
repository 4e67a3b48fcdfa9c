/* metrics_text.c — writes the exposition: one family after another, each with
 * its HELP and TYPE lines, names prefixed fluidcast_ (process_start_time_seconds
 * is the name every exporter uses). */
#include "metrics/metrics_text.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A growing string; `failed` once out of memory, after which appends do nothing. */
typedef struct text {
    char *data;
    size_t length, capacity;
    bool failed;
} text;

static void append(text *t, const char *format, ...) __attribute__((format(printf, 2, 3)));
static void append(text *t, const char *format, ...)
{
    for (int attempt = 0; attempt < 2 && !t->failed; attempt++) {
        va_list args;
        va_start(args, format);
        int n = vsnprintf(t->data + t->length, t->capacity - t->length, format, args);
        va_end(args);
        if (n < 0) {
            t->failed = true;
        } else if ((size_t)n < t->capacity - t->length) {
            t->length += (size_t)n;
            return;
        } else {
            size_t capacity = (t->capacity + (size_t)n + 1) * 2;
            char *data = realloc(t->data, capacity);
            t->failed = data == NULL;
            if (data) {
                t->data = data;
                t->capacity = capacity;
            }
        }
    }
}

static void family(text *t, const char *name, const char *type, const char *help)
{
    append(t, "# HELP %s %s\n# TYPE %s %s\n", name, help, name, type);
}

static void counter(text *t, fc_metrics *m, const char *name, fc_metric_counter c, const char *help)
{
    family(t, name, "counter", help);
    append(t, "%s %llu\n", name, (unsigned long long)fc_metrics_counter(m, c));
}

static void gauge(text *t, const char *name, long long value, const char *help)
{
    family(t, name, "gauge", help);
    append(t, "%s %lld\n", name, value);
}

/* A label value with \, " and newlines escaped, as the format requires. */
static void append_label_value(text *t, const char *value)
{
    append(t, "\"");
    for (const char *p = value; *p; p++) {
        if (*p == '\\' || *p == '"')
            append(t, "\\%c", *p);
        else if (*p == '\n')
            append(t, "\\n");
        else
            append(t, "%c", *p);
    }
    append(t, "\"");
}

static void histogram(text *t, fc_metrics *m, const char *name, fc_metric_histogram h, const char *help)
{
    fc_metrics_histogram_snapshot s;
    fc_metrics_histogram(m, h, &s);
    family(t, name, "histogram", help);
    /* _count is the sum of the buckets read, so it equals the +Inf bucket
     * even while observations are being added. */
    unsigned long long cumulative = 0;
    for (int b = 0; b < FC_METRIC_BUCKETS; b++) {
        cumulative += s.buckets[b];
        append(t, "%s_bucket{le=\"%g\"} %llu\n", name, fc_metric_bucket_bounds[b], cumulative);
    }
    cumulative += s.buckets[FC_METRIC_BUCKETS];
    append(t, "%s_bucket{le=\"+Inf\"} %llu\n%s_sum %.9f\n%s_count %llu\n", name, cumulative, name, s.sum_seconds,
           name, cumulative);
}

static void frames_dropped(text *t, fc_metrics *m)
{
    static const struct {
        const char *reason;
        fc_metric_counter counter;
    } reasons[] = {{"viewer_busy", FC_METRIC_DROPPED_VIEWER_BUSY},
                   {"render_failed", FC_METRIC_DROPPED_RENDER_FAILED},
                   {"client_gone", FC_METRIC_DROPPED_CLIENT_GONE}};
    family(t, "fluidcast_frames_dropped_total", "counter",
           "Frames not delivered, by reason: viewer_busy (a viewer still had an image in flight: latest wins), "
           "render_failed (GPU or encoder error), client_gone (the connection closed first).");
    for (size_t i = 0; i < sizeof reasons / sizeof reasons[0]; i++)
        append(t, "fluidcast_frames_dropped_total{reason=\"%s\"} %llu\n", reasons[i].reason,
               (unsigned long long)fc_metrics_counter(m, reasons[i].counter));
}

static void build_info(text *t, fc_metrics *m)
{
    fc_metrics_build_info info;
    fc_metrics_build_info_get(m, &info);
    family(t, "fluidcast_build_info", "gauge",
           "Always 1; the labels name the daemon's version, its GL renderer and GPU device.");
    append(t, "fluidcast_build_info{version=");
    append_label_value(t, info.version);
    append(t, ",renderer=");
    append_label_value(t, info.renderer);
    append(t, ",device=");
    append_label_value(t, info.device);
    append(t, "} 1\n");
}

static void gauges(text *t, fc_metrics *m)
{
    gauge(t, "fluidcast_ready", fc_metrics_phase(m) == FC_PHASE_SERVING,
          "1 while serving; 0 while starting (no GL context yet) or draining after SIGTERM.");
    gauge(t, "fluidcast_connections", fc_metrics_gauge(m, FC_METRIC_CONNECTIONS), "Client connections open.");
    gauge(t, "fluidcast_sessions", fc_metrics_gauge(m, FC_METRIC_SESSIONS), "Named sessions.");
    /* Absent, not 0, when the driver does not tell (llvmpipe). */
    long long total = fc_metrics_gauge(m, FC_METRIC_GPU_MEMORY_TOTAL);
    long long available = fc_metrics_gauge(m, FC_METRIC_GPU_MEMORY_AVAILABLE);
    if (total >= 0)
        gauge(t, "fluidcast_gpu_memory_total_bytes", total, "Dedicated memory of the GPU, as its driver reports.");
    if (available >= 0)
        gauge(t, "fluidcast_gpu_memory_available_bytes", available,
              "GPU memory available, as its driver reports (after the last render).");
    family(t, "process_start_time_seconds", "gauge", "Start time of the process since the Unix epoch in seconds.");
    append(t, "process_start_time_seconds %.3f\n", fc_metrics_start_time(m));
}

static void counters(text *t, fc_metrics *m)
{
    counter(t, m, "fluidcast_connections_accepted_total", FC_METRIC_CONNECTIONS_ACCEPTED, "Client connections accepted.");
    counter(t, m, "fluidcast_messages_received_total", FC_METRIC_MESSAGES_RECEIVED, "Protocol messages received.");
    counter(t, m, "fluidcast_received_bytes_total", FC_METRIC_BYTES_RECEIVED, "Bytes received from clients.");
    counter(t, m, "fluidcast_sent_bytes_total", FC_METRIC_BYTES_SENT, "Bytes sent to clients.");
    counter(t, m, "fluidcast_frames_rendered_total", FC_METRIC_FRAMES_RENDERED,
            "Images rendered and encoded (IMAGE and STREAM_IMAGE replies).");
    frames_dropped(t, m);
    counter(t, m, "fluidcast_limit_rejections_total", FC_METRIC_LIMIT_REJECTIONS,
            "Requests refused with ERROR LIMIT (connections, sizes, memory, sessions, timeouts).");
    counter(t, m, "fluidcast_tls_handshakes_total", FC_METRIC_TLS_HANDSHAKES, "TLS handshakes completed.");
    counter(t, m, "fluidcast_tls_handshake_failures_total", FC_METRIC_TLS_HANDSHAKE_FAILURES,
            "TLS handshakes that failed, and clients without TLS refused on a TLS port.");
    counter(t, m, "fluidcast_tls_handshake_timeouts_total", FC_METRIC_TLS_HANDSHAKE_TIMEOUTS,
            "TLS handshakes dropped because they did not complete within the handshake timeout.");
}

char *fc_metrics_text(fc_metrics *m, size_t *length)
{
    text t = {0};
    build_info(&t, m);
    gauges(&t, m);
    counters(&t, m);
    histogram(&t, m, "fluidcast_render_seconds", FC_METRIC_RENDER_SECONDS,
              "GPU time of one image: particle upload through readback.");
    histogram(&t, m, "fluidcast_encode_seconds", FC_METRIC_ENCODE_SECONDS, "Time to encode one image.");
    if (t.failed || !t.data) {
        free(t.data);
        return NULL;
    }
    *length = t.length;
    return t.data;
}
