/* metrics_http.h — the daemon's HTTP endpoint for operators, on its own
 * listening socket (never a render port), served by libmicrohttpd on a thread
 * of its own, so it answers while the GL context is being created and while
 * the event loop is busy:
 *   GET /metrics  the metrics in Prometheus' text format (metrics_text.h)
 *   GET /healthz  200 "ok" while the process runs
 *   GET /readyz   200 "ready" while serving; 503 while starting (no GL context
 *                 or listener yet) or draining after SIGTERM
 * HEAD answers like GET without the body; other methods get 405 with Allow,
 * other paths 404. */
#ifndef FC_DAEMON_METRICS_HTTP_H
#define FC_DAEMON_METRICS_HTTP_H

#include "fluidcast_types.h"
#include "metrics/metrics.h"

typedef struct fc_metrics_http fc_metrics_http;

/* Serves on listen_fd, a listening TCP socket (taken over: closed by
 * fc_metrics_http_stop): over HTTPS when cert_file and key_file (PEM) are
 * given, read once here; over HTTP when they are NULL. metrics must outlive
 * the server. FC_ERR_USAGE naming a file that cannot be read; FC_ERR_IO when
 * libmicrohttpd cannot start (or take the certificate). */
fc_code fc_metrics_http_start(int listen_fd, fc_metrics *metrics, const char *cert_file, const char *key_file,
                              fc_metrics_http **out, fc_error *err);
/* Stops the thread, closes the socket; NULL is fine. */
void fc_metrics_http_stop(fc_metrics_http *server);

#endif
