/* metrics_http.c — /metrics, /healthz and /readyz over libmicrohttpd. */
#include "metrics/metrics_http.h"

#include <microhttpd.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_file.h"
#include "metrics/metrics_text.h"

/* A scraper or a probe needs one connection; a few more are room for several,
 * and the limit keeps a flood from costing threads or memory. */
enum { MAX_CONNECTIONS = 32, CONNECTION_TIMEOUT_S = 10 };
/* A PEM certificate chain or key is a few KiB; this bounds a wrong path's cost. */
#define MAX_PEM_BYTES ((size_t)1 << 20)

#if MHD_VERSION < 0x00097002
typedef int fc_mhd_result;
#else
typedef enum MHD_Result fc_mhd_result;
#endif

struct fc_metrics_http {
    struct MHD_Daemon *daemon;
    int listen_fd;
    fc_metrics *metrics;
    uint8_t *cert_pem, *key_pem;   /* HTTPS: the PEM files as libmicrohttpd was given them; NULL: HTTP */
};

static fc_mhd_result respond(struct MHD_Connection *connection, unsigned status, const char *content_type,
                             char *body, size_t length, enum MHD_ResponseMemoryMode mode, const char *allow)
{
    struct MHD_Response *response = MHD_create_response_from_buffer(length, body, mode);
    if (!response) {
        if (mode == MHD_RESPMEM_MUST_FREE)
            free(body);
        return MHD_NO;
    }
    MHD_add_response_header(response, MHD_HTTP_HEADER_CONTENT_TYPE, content_type);
    /* Probes and scrapes want the state now, never a cached answer. */
    MHD_add_response_header(response, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    if (allow)
        MHD_add_response_header(response, MHD_HTTP_HEADER_ALLOW, allow);
    fc_mhd_result result = MHD_queue_response(connection, status, response);
    MHD_destroy_response(response);
    return result;
}

static fc_mhd_result respond_text(struct MHD_Connection *connection, unsigned status, const char *text,
                                  const char *allow)
{
    return respond(connection, status, "text/plain; charset=utf-8", (char *)text, strlen(text),
                   MHD_RESPMEM_PERSISTENT, allow);
}

static fc_mhd_result serve_metrics(struct MHD_Connection *connection, fc_metrics *metrics)
{
    size_t length = 0;
    char *body = fc_metrics_text(metrics, &length);
    if (!body)
        return respond_text(connection, MHD_HTTP_INTERNAL_SERVER_ERROR, "out of memory\n", NULL);
    return respond(connection, MHD_HTTP_OK, FC_METRICS_CONTENT_TYPE, body, length, MHD_RESPMEM_MUST_FREE, NULL);
}

static fc_mhd_result serve_ready(struct MHD_Connection *connection, fc_metrics *metrics)
{
    switch (fc_metrics_phase(metrics)) {
    case FC_PHASE_SERVING:
        return respond_text(connection, MHD_HTTP_OK, "ready\n", NULL);
    case FC_PHASE_DRAINING:
        return respond_text(connection, MHD_HTTP_SERVICE_UNAVAILABLE, "draining: stopping after SIGTERM\n", NULL);
    case FC_PHASE_STARTING:
    default:
        return respond_text(connection, MHD_HTTP_SERVICE_UNAVAILABLE, "starting: no GL context or listener yet\n",
                            NULL);
    }
}

/* Called by libmicrohttpd once a request's headers are in; the request is
 * answered right then (no endpoint takes a body: one sent is discarded). */
static fc_mhd_result on_request(void *closure, struct MHD_Connection *connection, const char *url,
                                const char *method, const char *version, const char *upload_data,
                                size_t *upload_data_size, void **request_state)
{
    (void)version;
    (void)upload_data;
    (void)request_state;
    fc_metrics *metrics = closure;
    *upload_data_size = 0;
    if (strcmp(method, MHD_HTTP_METHOD_GET) != 0 && strcmp(method, MHD_HTTP_METHOD_HEAD) != 0)
        return respond_text(connection, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed: use GET or HEAD\n",
                            "GET, HEAD");
    if (strcmp(url, "/metrics") == 0)
        return serve_metrics(connection, metrics);
    if (strcmp(url, "/healthz") == 0)
        return respond_text(connection, MHD_HTTP_OK, "ok\n", NULL);
    if (strcmp(url, "/readyz") == 0)
        return serve_ready(connection, metrics);
    return respond_text(connection, MHD_HTTP_NOT_FOUND, "not found: /metrics, /healthz or /readyz\n", NULL);
}

static void free_server(fc_metrics_http *server)
{
    free(server->cert_pem);
    free(server->key_pem);
    free(server);
}

/* HTTPS: the certificate and key in memory, as libmicrohttpd takes them. */
static fc_code read_pems(fc_metrics_http *server, const char *cert_file, const char *key_file, fc_error *err)
{
    size_t size;
    fc_error why;
    if (fc_read_file(cert_file, MAX_PEM_BYTES, &server->cert_pem, &size, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "--metrics-tls: --tls-cert %s", why.message);
    if (fc_read_file(key_file, MAX_PEM_BYTES, &server->key_pem, &size, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "--metrics-tls: --tls-key %s", why.message);
    return FC_OK;
}

static struct MHD_Daemon *start_mhd(fc_metrics_http *server)
{
    /* HTTPS adds the certificate and key; over HTTP the list is empty. */
    struct MHD_OptionItem https[] = {{MHD_OPTION_HTTPS_MEM_CERT, 0, server->cert_pem},
                                     {MHD_OPTION_HTTPS_MEM_KEY, 0, server->key_pem},
                                     {MHD_OPTION_END, 0, NULL}};
    bool tls = server->cert_pem != NULL;
    /* One internal thread polls every connection: a scrape is small and rare. */
    unsigned flags = MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_POLL | (tls ? MHD_USE_TLS : 0);
    return MHD_start_daemon(flags, 0, NULL, NULL, on_request, server->metrics, MHD_OPTION_LISTEN_SOCKET,
                            server->listen_fd, MHD_OPTION_CONNECTION_LIMIT, (unsigned)MAX_CONNECTIONS,
                            MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)CONNECTION_TIMEOUT_S, MHD_OPTION_ARRAY,
                            tls ? https : https + 2, MHD_OPTION_END);
}

fc_code fc_metrics_http_start(int listen_fd, fc_metrics *metrics, const char *cert_file, const char *key_file,
                              fc_metrics_http **out, fc_error *err)
{
    fc_metrics_http *server = calloc(1, sizeof *server);
    if (!server) {
        close(listen_fd);
        return fc_error_set(err, FC_ERR_NOMEM, "metrics endpoint: out of memory");
    }
    server->listen_fd = listen_fd;
    server->metrics = metrics;
    fc_code code = cert_file ? read_pems(server, cert_file, key_file, err) : FC_OK;
    if (code == FC_OK && !(server->daemon = start_mhd(server)))
        code = fc_error_set(err, FC_ERR_IO, "metrics endpoint: libmicrohttpd cannot start on its socket%s",
                            cert_file ? " with the certificate (is it built with TLS?)" : "");
    if (code != FC_OK) {
        close(listen_fd);
        free_server(server);
        return code;
    }
    *out = server;
    return FC_OK;
}

void fc_metrics_http_stop(fc_metrics_http *server)
{
    if (!server)
        return;
    MHD_stop_daemon(server->daemon);
    /* MHD_stop_daemon closes the listening socket too, the one it was given
     * included (it was never quiesced), so no close() here. */
    free_server(server);
}
