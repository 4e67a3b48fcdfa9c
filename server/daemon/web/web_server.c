/* web_server.c — the web viewer's HTTP and WebSocket endpoint (web_server.h). */
#include "web/web_server.h"

#include <errno.h>
#include <fcntl.h>
#include <libwebsockets.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fc_colormap.h"
#include "fc_error.h"
#include "net/tls_server.h"
#include "web/web_assets.h"
#include "web/web_relay.h"

#define ACCEPT_PROTOCOL "fluidcast-accept"

/* Everything the page needs comes from this origin, nothing runs inline, and
 * no other site may frame it: what a page injected into it could do is
 * limited to this daemon's own files and WebSocket. */
static const char CONTENT_SECURITY_POLICY[] =
    "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; connect-src 'self'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

enum { HTTP_BODY_CHUNK = 16 * 1024, PROTOCOL_COUNT = 4 };

struct fc_web_server {
    fc_web_relay_config relay_config;   /* first: the context's user pointer is both it and the server */
    char *colormaps_json;               /* /colormaps.json: the colormaps' tables, for the page's legend */
    fc_web_asset colormaps;
    const fc_log *log;
    fc_listener web;                    /* fd -1 once libwebsockets owns it */
    fc_listener relay;
    fc_tls_server *tls;                 /* the listeners' certificate: https:// and wss://; NULL: http:// */
    char relay_dir[64];                 /* "" when not made */
    char relay_path[108];
    struct lws_protocols protocols[PROTOCOL_COUNT + 1];
    struct lws_context *context;
    struct lws_vhost *vhost;
    pthread_t thread;
    bool thread_started;
    atomic_bool stopping;
};

typedef struct http_reply {
    const fc_web_asset *asset;
    size_t sent;
    bool head;      /* HEAD: the headers only */
} http_reply;

static const fc_web_server *server_of(struct lws *wsi)
{
    return lws_context_user(lws_get_context(wsi));
}

static const fc_log *log_of(struct lws *wsi)
{
    return server_of(wsi)->log;
}

/* The colormaps' tables (fc_colormap.h) as JSON, [{"name": ..., "colors": [[r, g, b], ...]}, ...]: the
 * page draws its legend from the tables the renderer colours with. */
static fc_code make_colormaps_json(fc_web_server *s, fc_error *err)
{
    size_t cap = (size_t)FC_COLORMAP_COUNT * (FC_COLORMAP_ENTRIES * 24 + 64), used = 0;
    char *json = malloc(cap);
    if (!json)
        return fc_error_set(err, FC_ERR_NOMEM, "web: out of memory");
    used += (size_t)snprintf(json + used, cap - used, "[");
    for (int m = 0; m < FC_COLORMAP_COUNT; m++) {
        const float(*table)[3] = fc_colormap_table((fc_colormap)m);
        used += (size_t)snprintf(json + used, cap - used, "%s{\"name\":\"%s\",\"colors\":[", m ? "," : "",
                                 fc_colormap_name((fc_colormap)m));
        for (int i = 0; i < FC_COLORMAP_ENTRIES; i++)
            used += (size_t)snprintf(json + used, cap - used, "%s[%.4f,%.4f,%.4f]", i ? "," : "",
                                     (double)table[i][0], (double)table[i][1], (double)table[i][2]);
        used += (size_t)snprintf(json + used, cap - used, "]}");
    }
    used += (size_t)snprintf(json + used, cap - used, "]");
    s->colormaps_json = json;
    s->colormaps = (fc_web_asset){"/colormaps.json", "application/json", (const unsigned char *)json, used};
    return FC_OK;
}

static const fc_web_asset *find_asset(struct lws *wsi, const char *path)
{
    const fc_web_server *s = server_of(wsi);
    return strcmp(path, s->colormaps.path) == 0 ? &s->colormaps : fc_web_asset_find(path);
}

static int add_header(struct lws *wsi, const char *name, const char *value, unsigned char **p, unsigned char *end)
{
    return lws_add_http_header_by_name(wsi, (const unsigned char *)name, (const unsigned char *)value,
                                       (int)strlen(value), p, end);
}

/* Done with one request: keep the connection for the next, or close it. */
static int transaction_done(struct lws *wsi)
{
    return lws_http_transaction_completed(wsi) ? -1 : 0;
}

static int start_reply(struct lws *wsi, http_reply *reply, const char *path)
{
    reply->head = lws_hdr_total_length(wsi, WSI_TOKEN_HEAD_URI) > 0;
    if (!reply->head && lws_hdr_total_length(wsi, WSI_TOKEN_GET_URI) <= 0) {
        lws_return_http_status(wsi, HTTP_STATUS_METHOD_NOT_ALLOWED, NULL);
        return transaction_done(wsi);
    }
    reply->asset = find_asset(wsi, path);
    reply->sent = 0;
    if (!reply->asset) {
        lws_return_http_status(wsi, HTTP_STATUS_NOT_FOUND, NULL);
        return transaction_done(wsi);
    }
    unsigned char buffer[LWS_PRE + 2048];
    unsigned char *start = buffer + LWS_PRE, *p = start, *end = buffer + sizeof buffer - 1;
    if (lws_add_http_common_headers(wsi, HTTP_STATUS_OK, reply->asset->content_type, reply->asset->size, &p,
                                    end) ||
        add_header(wsi, "content-security-policy:", CONTENT_SECURITY_POLICY, &p, end) ||
        add_header(wsi, "x-content-type-options:", "nosniff", &p, end) ||
        add_header(wsi, "x-frame-options:", "DENY", &p, end) ||
        add_header(wsi, "referrer-policy:", "no-referrer", &p, end) ||
        add_header(wsi, "cache-control:", "no-store", &p, end) ||
        lws_finalize_write_http_header(wsi, start, &p, end))
        return -1;
    if (reply->head)
        return transaction_done(wsi);
    lws_callback_on_writable(wsi);
    return 0;
}

static int write_body(struct lws *wsi, http_reply *reply)
{
    if (!reply->asset)
        return 0;
    unsigned char buffer[LWS_PRE + HTTP_BODY_CHUNK];
    size_t n = reply->asset->size - reply->sent;
    if (n > HTTP_BODY_CHUNK)
        n = HTTP_BODY_CHUNK;
    bool last = reply->sent + n == reply->asset->size;
    memcpy(buffer + LWS_PRE, reply->asset->data + reply->sent, n);
    if (lws_write(wsi, buffer + LWS_PRE, n, last ? LWS_WRITE_HTTP_FINAL : LWS_WRITE_HTTP) != (int)n)
        return -1;
    reply->sent += n;
    if (!last) {
        lws_callback_on_writable(wsi);
        return 0;
    }
    reply->asset = NULL;
    return transaction_done(wsi);
}

/* A browser opening the WebSocket from a page of another site is refused
 * (cross-site WebSocket hijacking): its Origin must name this Host. Clients
 * that send no Origin (not browsers) are let through; the token still applies. */
static bool same_origin(struct lws *wsi)
{
    char origin[256], host[256];
    if (lws_hdr_copy(wsi, origin, sizeof origin, WSI_TOKEN_ORIGIN) <= 0)
        return true;
    if (lws_hdr_copy(wsi, host, sizeof host, WSI_TOKEN_HOST) <= 0)
        return false;
    const char *rest = strstr(origin, "://");
    bool same = rest && strcmp(rest + 3, host) == 0;
    if (!same)
        fc_log_write(log_of(wsi), FC_LOG_WARN, "web: WebSocket from origin '%s' refused (host '%s')", origin,
                     host);
    return same;
}

/* Every handshake takes the certificate and key the protocol listeners have
 * now (fc_tls_server_current), so that SIGHUP's reload reaches the web
 * listener too: libwebsockets loaded the files once, at the start. */
static int use_current_certificate(SSL *ssl, void *arg)
{
    SSL_CTX *current = fc_tls_server_current(arg);
    bool swapped = SSL_set_SSL_CTX(ssl, current) == current;
    SSL_CTX_free(current);   /* the session holds its own reference */
    return swapped;
}

static int http_callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in, size_t len)
{
    (void)len;
    switch (reason) {
    case LWS_CALLBACK_OPENSSL_LOAD_EXTRA_SERVER_VERIFY_CERTS:   /* user: the host's SSL_CTX */
        SSL_CTX_set_cert_cb(user, use_current_certificate, server_of(wsi)->tls);
        return 0;
    case LWS_CALLBACK_HTTP:
        return start_reply(wsi, user, in);
    case LWS_CALLBACK_HTTP_WRITEABLE:
        return write_body(wsi, user);
    case LWS_CALLBACK_FILTER_PROTOCOL_CONNECTION:
        return same_origin(wsi) ? 0 : 1;
    default:
        return 0;
    }
}

static int ws_callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in, size_t len)
{
    if (reason == LWS_CALLBACK_FILTER_PROTOCOL_CONNECTION)
        return same_origin(wsi) ? 0 : 1;
    return fc_web_relay_ws_callback(wsi, reason, user, in, len);
}

/* The web listener is a raw descriptor of libwebsockets: when it is readable,
 * each waiting browser connection is accepted and adopted as HTTP. */
static int accept_callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in, size_t len)
{
    (void)user;
    (void)in;
    (void)len;
    if (reason != LWS_CALLBACK_RAW_RX_FILE)
        return 0;
    for (;;) {
        int fd = accept(lws_get_socket_fd(wsi), NULL, NULL);
        if (fd >= 0 && fcntl(fd, F_SETFD, FD_CLOEXEC) != 0) {
            close(fd);
            continue;
        }
        if (fd < 0) {
            if (errno != EAGAIN && errno != EWOULDBLOCK && errno != ECONNABORTED && errno != EINTR)
                fc_log_write(log_of(wsi), FC_LOG_WARN, "web: accept: %s", strerror(errno));
            return 0;
        }
        lws_adopt_socket_vhost(lws_get_vhost(wsi), fd);   /* closes fd on failure */
    }
}

static void fill_protocols(fc_web_server *s)
{
    s->protocols[0] = (struct lws_protocols){"http", http_callback, sizeof(http_reply), 0, 0, NULL, 0};
    s->protocols[1] =
        (struct lws_protocols){FC_WEB_SUBPROTOCOL, ws_callback, fc_web_relay_size(), 64 * 1024, 0, NULL, 0};
    s->protocols[2] =
        (struct lws_protocols){FC_WEB_RELAY_PROTOCOL, fc_web_relay_daemon_callback, 0, 0, 0, NULL, 0};
    s->protocols[3] = (struct lws_protocols){ACCEPT_PROTOCOL, accept_callback, 0, 0, 0, NULL, 0};
    memset(&s->protocols[PROTOCOL_COUNT], 0, sizeof s->protocols[PROTOCOL_COUNT]);
}

/* The relay listener in a fresh folder of mode 0700: only the daemon's user
 * can connect to it, so it opens no way in that the web port does not. */
static fc_code open_relay(fc_web_server *s, fc_error *err)
{
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !tmp[0] || strlen(tmp) > 40)
        tmp = "/tmp";
    snprintf(s->relay_dir, sizeof s->relay_dir, "%s/fluidcastd-web.XXXXXX", tmp);
    if (!mkdtemp(s->relay_dir)) {
        s->relay_dir[0] = '\0';
        return fc_error_set(err, FC_ERR_IO, "web: cannot make the relay socket's folder: %s", strerror(errno));
    }
    snprintf(s->relay_path, sizeof s->relay_path, "%s/relay.sock", s->relay_dir);
    s->relay_config.relay_path = s->relay_path;
    return fc_listener_open_unix(s->relay_path, &s->relay, err);
}

/* With the protocol listeners' certificate (--tls-cert, --tls-key) the page
 * and its WebSocket are served over TLS only: https:// and wss://, with the
 * same floor as the protocol listeners (TLS 1.2, net/tls_server.c) and, with
 * --tls-client-ca, the same demand for a client certificate. A plain HTTP
 * request on that port fails its handshake. */
static void set_vhost_tls(const fc_tls_server_files *tls, struct lws_context_creation_info *info)
{
    /* libwebsockets needs the files to start TLS on the host; the handshakes
     * then use the listeners' context (use_current_certificate). */
    info->ssl_cert_filepath = tls->cert_file;
    info->ssl_private_key_filepath = tls->key_file;
    info->ssl_options_set = SSL_OP_NO_TLSv1 | SSL_OP_NO_TLSv1_1;
    /* HTTP/1.1 only: libwebsockets 4.1's HTTP/2 on an adopted socket resets
     * the connection at a second request (a browser's page, then its scripts). */
    info->alpn = "http/1.1";
    if (tls->client_ca_file) {
        info->ssl_ca_filepath = tls->client_ca_file;
        info->options |= LWS_SERVER_OPTION_REQUIRE_VALID_OPENSSL_CLIENT_CERT;
    }
}

static fc_code start_lws(fc_web_server *s, fc_error *err)
{
    fill_protocols(s);
    lws_set_log_level(LLL_ERR, NULL);
    struct lws_context_creation_info info;
    memset(&info, 0, sizeof info);
    const fc_tls_server_files *tls = s->tls ? fc_tls_server_paths(s->tls) : NULL;
    info.options = LWS_SERVER_OPTION_EXPLICIT_VHOSTS | (tls ? LWS_SERVER_OPTION_DO_SSL_GLOBAL_INIT : 0);
    info.port = CONTEXT_PORT_NO_LISTEN_SERVER;
    info.protocols = s->protocols;
    info.user = s;
    info.gid = (gid_t)-1;
    info.uid = (uid_t)-1;
    s->context = lws_create_context(&info);
    if (!s->context)
        return fc_error_set(err, FC_ERR_IO, "web: libwebsockets cannot start");
    info.vhost_name = "fluidcast";
    if (tls)
        set_vhost_tls(tls, &info);
    s->vhost = lws_create_vhost(s->context, &info);
    if (!s->vhost && tls)
        return fc_error_set(err, FC_ERR_IO, "web: libwebsockets cannot make its host with the certificate %s and "
                            "the key %s", tls->cert_file, tls->key_file);
    if (!s->vhost)
        return fc_error_set(err, FC_ERR_IO, "web: libwebsockets cannot make its host");
    lws_sock_file_fd_type fd = {.filefd = s->web.fd};
    struct lws *listener = lws_adopt_descriptor_vhost(s->vhost, LWS_ADOPT_RAW_FILE_DESC, fd, ACCEPT_PROTOCOL, NULL);
    s->web.fd = -1;   /* libwebsockets closes it, on failure too */
    if (!listener)
        return fc_error_set(err, FC_ERR_IO, "web: libwebsockets cannot take the listening socket");
    return FC_OK;
}

static void *serve(void *arg)
{
    fc_web_server *s = arg;
    while (!atomic_load(&s->stopping))
        if (lws_service(s->context, 0) < 0)
            break;
    return NULL;
}

fc_code fc_web_server_start(const char *host, const char *port, fc_tls_server *tls, const fc_log *log,
                            fc_web_server **out, fc_error *err)
{
    fc_web_server *s = calloc(1, sizeof *s);
    if (!s)
        return fc_error_set(err, FC_ERR_NOMEM, "web: out of memory");
    s->log = log;
    s->tls = tls;
    s->relay_config.log = log;
    s->web.fd = s->relay.fd = -1;
    atomic_init(&s->stopping, false);
    fc_error open_err;
    fc_code code = fc_listener_open(host, port, &s->web, &open_err);
    if (code != FC_OK)
        code = fc_error_set(err, FC_ERR_IO, "--web-listen: %s", open_err.message);
    if (code == FC_OK)
        code = make_colormaps_json(s, err);
    if (code == FC_OK)
        code = open_relay(s, err);
    if (code == FC_OK)
        code = start_lws(s, err);
    if (code == FC_OK && pthread_create(&s->thread, NULL, serve, s) != 0)
        code = fc_error_set(err, FC_ERR_IO, "web: cannot start its thread");
    s->thread_started = code == FC_OK;
    if (code != FC_OK) {
        fc_web_server_stop(s);
        return code;
    }
    *out = s;
    return FC_OK;
}

const fc_listener *fc_web_server_relay(const fc_web_server *server)
{
    return &server->relay;
}

const char *fc_web_server_address(const fc_web_server *server)
{
    return server->web.address;
}

const char *fc_web_server_scheme(const fc_web_server *server)
{
    return server->tls ? "https" : "http";
}

void fc_web_server_stop(fc_web_server *server)
{
    if (!server)
        return;
    if (server->thread_started) {
        atomic_store(&server->stopping, true);
        lws_cancel_service(server->context);
        pthread_join(server->thread, NULL);
    }
    if (server->context)
        lws_context_destroy(server->context);
    fc_listener_close(&server->web);
    fc_listener_close(&server->relay);
    if (server->relay_dir[0])
        rmdir(server->relay_dir);
    free(server->colormaps_json);
    free(server);
}
