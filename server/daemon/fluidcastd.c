/* fluidcastd.c — the render daemon's top level: options, signals, the render
 * service (GL thread and encoders), the named sessions, the listeners and the
 * event loop, in that order, telling a service manager (systemd) how far it
 * got (service_manager.h); exit 0 on SIGINT/SIGTERM, 1 when it cannot start,
 * 2 on a bad command line; SIGHUP reloads the TLS certificate and key. The folders below (net/, conversations/, sessions/, gpu/,
 * uploads/) are the daemon's layers: README.md maps them. */
#include <arpa/inet.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include "auth_token.h"
#include "daemon_context.h"
#include "fc_error.h"
#include "gpu/encoder_pool.h"
#include "net/event_loop.h"
#include "net/listener.h"
#include "net/tls_server.h"
#include "metrics/metrics.h"
#include "metrics/metrics_http.h"
#include "options.h"
#include "service_manager.h"
#include "web/web_server.h"
#include "uploads/frame_pool.h"

#define FLUIDCASTD_VERSION "0.1.0"
#define SERVER_VERSION "fluidcastd " FLUIDCASTD_VERSION

/* EXIT_FAILURE (1): cannot start or keep serving. */
/* MAX_LISTENERS: --listen and --unix, or as many as a .socket unit passes. */
enum { EXIT_BAD_USAGE = 2, MAX_LISTENERS = 8 };

/* What the frame pool may keep waiting between frames: a stream needs about
 * three blocks (the frame being received, the newest, the one being
 * rendered), so a few streams of frames up to tens of megabytes recycle all
 * of theirs; an idle daemon keeps no more than this. */
#define FRAME_POOL_BLOCKS 8
#define FRAME_POOL_BYTES ((size_t)256 << 20)

/* SIGINT/SIGTERM (stop) and SIGHUP (reload the TLS files) are blocked and
 * read from signalfds the event loop polls: no handler, no global flag.
 * Blocked before any thread exists (llvmpipe and OpenImageIO start their
 * own), since threads inherit the mask and a thread without it would let the
 * signal kill the process. */
static int open_signals(int first, int second, fc_error *err)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, first);
    if (second)
        sigaddset(&set, second);
    if (sigprocmask(SIG_BLOCK, &set, NULL) != 0) {
        fc_error_set(err, FC_ERR_IO, "sigprocmask: %s", strerror(errno));
        return -1;
    }
    int fd = signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
    if (fd < 0)
        fc_error_set(err, FC_ERR_IO, "signalfd: %s", strerror(errno));
    return fd;
}

static const char *received_signal_name(int signal_fd)
{
    struct signalfd_siginfo info;
    if (read(signal_fd, &info, sizeof info) != (ssize_t)sizeof info)
        return "a signal";
    return info.ssi_signo == SIGINT ? "SIGINT" : "SIGTERM";
}

/* Written to a temporary name and renamed, so a reader never sees half a number. */
static fc_code write_port_file(const char *path, unsigned port, fc_error *err)
{
    char tmp[4096];
    if ((size_t)snprintf(tmp, sizeof tmp, "%s.tmp", path) >= sizeof tmp)
        return fc_error_set(err, FC_ERR_USAGE, "--port-file path too long");
    FILE *f = fopen(tmp, "w");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "cannot write %s: %s", tmp, strerror(errno));
    int written = fprintf(f, "%u\n", port);
    if (fclose(f) != 0 || written < 0 || rename(tmp, path) != 0) {
        unlink(tmp);
        return fc_error_set(err, FC_ERR_IO, "cannot write the port file %s: %s", path, strerror(errno));
    }
    return FC_OK;
}

static void fill_welcome(const fc_daemon_options *options, const fc_render_service *render, fc_welcome *w)
{
    memset(w, 0, sizeof *w);
    w->version = FC_PROTOCOL_VERSION;
    w->limits = options->limits;
    snprintf(w->server_version, sizeof w->server_version, "%s", SERVER_VERSION);
    snprintf(w->renderer, sizeof w->renderer, "%s", fc_render_service_renderer(render));
    snprintf(w->device, sizeof w->device, "%s", fc_render_service_device(render));
}

static bool is_loopback_host(const char *host)
{
    struct in_addr v4;
    struct in6_addr v6;
    if (strcmp(host, "localhost") == 0)
        return true;
    if (inet_pton(AF_INET, host, &v4) == 1)
        return (ntohl(v4.s_addr) >> 24) == 127;
    return inet_pton(AF_INET6, host, &v6) == 1 && IN6_IS_ADDR_LOOPBACK(&v6);
}

/* Anyone who can reach a non-loopback port can use a daemon without a token:
 * say so, since it may be an oversight. */
static void warn_if_open(const fc_daemon_options *options, const fc_auth_token *token, const fc_log *log)
{
    if (fc_auth_token_required(token) || !fc_daemon_options_serve_tcp(options) ||
        is_loopback_host(options->listen_host))
        return;
    fc_log_write(log, FC_LOG_WARN,
                 "listening on %s without authentication: anyone who can reach it can use this daemon "
                 "(use --token-file or FLUIDCAST_TOKEN)",
                 options->listen_host);
}

/* Without TLS the token, the particles and the images cross the network in
 * clear: loud, since an operator may not know. A warning, not a refusal:
 * clusters with their own encrypted fabric or tunnels run this way on purpose
 * (docs/security.md). */
static void warn_if_clear(const fc_daemon_options *options, const fc_log *log)
{
    if (options->tls_cert || !fc_daemon_options_serve_tcp(options) || is_loopback_host(options->listen_host))
        return;
    fc_log_write(log, FC_LOG_WARN,
                 "listening on %s WITHOUT TLS: the token, the particle data and the images travel in clear "
                 "(use --tls-cert and --tls-key, docs/security.md)",
                 options->listen_host);
}

/* Opens the TCP and/or Unix listeners the options ask for; *count of them. */
static fc_code open_own_listeners(const fc_daemon_options *options, fc_listener *listeners, size_t *count,
                                  fc_error *err)
{
    *count = 0;
    fc_code code = FC_OK;
    if (fc_daemon_options_serve_tcp(options)) {
        code = fc_listener_open(options->listen_host, options->listen_port, &listeners[0], err);
        if (code == FC_OK)
            (*count)++;
    }
    if (code == FC_OK && options->unix_path) {
        code = fc_listener_open_unix(options->unix_path, &listeners[*count], err);
        if (code == FC_OK)
            (*count)++;
    }
    return code;
}

/* The port of the first TCP listener, 0 when all are Unix sockets. */
static unsigned first_tcp_port(const fc_listener *listeners, size_t count)
{
    for (size_t i = 0; i < count; i++)
        if (!listeners[i].is_unix)
            return listeners[i].port;
    return 0;
}

/* The daemon's sockets: render listeners (inherited from systemd or opened
 * here) and the metrics endpoint. */
typedef struct daemon_sockets {
    fc_listener listeners[MAX_LISTENERS];
    size_t count;
    bool inherited;            /* the listeners came from socket activation */
    int metrics_fd;            /* an inherited metrics socket until the endpoint takes it; -1 */
    fc_metrics_http *http;     /* the metrics endpoint; NULL when not asked for */
    fc_tls_server *tls;        /* every TCP listener's TLS (--tls-cert); NULL: in clear */
    int reload_fd;             /* SIGHUP's signalfd: reload the TLS files */
    fc_web_server *web;        /* the web viewer (--web-listen); NULL when not asked for */
    fc_listener served[MAX_LISTENERS + 1];   /* what the event loop accepts from: listeners, then the web relay */
    size_t served_count;
} daemon_sockets;

/* What systemd passed, if anything: taken first, before the slow GL start,
 * so that the variables are gone before any library thread could see them. */
static fc_code inherit_sockets(const fc_daemon_options *options, const fc_log *log, daemon_sockets *s,
                               fc_error *err)
{
    fc_code code = fc_service_listeners(s->listeners, MAX_LISTENERS, &s->count, &s->metrics_fd, err);
    s->inherited = code == FC_OK && s->count > 0;
    if (s->inherited)
        fc_log_write(log, FC_LOG_INFO, "socket activation: serving on the %zu socket(s) the service manager passed%s",
                     s->count, options->listen_given || options->unix_path ? " (--listen and --unix ignored)" : "");
    return code;
}

/* The metrics endpoint, on an inherited socket named "metrics" or on
 * --metrics-listen; started before the GL context so that /readyz can say
 * the daemon is starting. A busy port is an error: the operator asked for it. */
static fc_code start_metrics(const fc_daemon_options *options, const fc_log *log, fc_metrics *metrics,
                             daemon_sockets *s, fc_error *err)
{
    fc_listener l = {.fd = s->metrics_fd};
    fc_error open_err;
    if (s->metrics_fd >= 0)
        snprintf(l.address, sizeof l.address, "the inherited socket '%s'", FC_SERVICE_METRICS_FD_NAME);
    else if (!options->metrics_host[0])
        return FC_OK;
    else if (fc_listener_open(options->metrics_host, options->metrics_port, &l, &open_err) != FC_OK)
        return fc_error_set(err, FC_ERR_IO, "--metrics-listen: %s", open_err.message);
    s->metrics_fd = -1;   /* the endpoint owns it now, started or not */
    bool https = options->metrics_tls;
    fc_code code = fc_metrics_http_start(l.fd, metrics, https ? options->tls_cert : NULL,
                                         https ? options->tls_key : NULL, &s->http, err);
    if (code == FC_OK)
        fc_log_write(log, FC_LOG_INFO, "metrics, health and readiness on %s://%s/metrics, /healthz, /readyz",
                     https ? "https" : "http", l.address);
    return code;
}

static void close_sockets(daemon_sockets *s)
{
    fc_web_server_stop(s->web);
    s->web = NULL;
    fc_metrics_http_stop(s->http);
    s->http = NULL;
    if (s->metrics_fd >= 0)
        close(s->metrics_fd);
    s->metrics_fd = -1;
    for (size_t i = 0; i < s->count; i++)
        fc_listener_close(&s->listeners[i]);
    s->count = 0;
}

/* The web viewer, when asked for: its relay listener joins those the event
 * loop serves, so that a browser's connection is a connection like any other. */
static fc_code start_web(const fc_daemon_options *options, const fc_log *log, daemon_sockets *s, fc_error *err)
{
    memcpy(s->served, s->listeners, s->count * sizeof s->listeners[0]);
    s->served_count = s->count;
    if (!options->web_host[0])
        return FC_OK;
    fc_code code = fc_web_server_start(options->web_host, options->web_port, s->tls, log, &s->web, err);
    if (code == FC_OK)
        s->served[s->served_count++] = *fc_web_server_relay(s->web);
    return code;
}

/* The listeners the options ask for, unless systemd passed some; TLS on the
 * TCP ones when asked for; then the port file and the web viewer. */
static fc_code open_listeners(const fc_daemon_options *options, const fc_log *log, daemon_sockets *s,
                              fc_error *err)
{
    fc_code code = s->inherited ? FC_OK : open_own_listeners(options, s->listeners, &s->count, err);
    for (size_t i = 0; i < s->count; i++)
        s->listeners[i].tls = s->listeners[i].is_unix ? NULL : s->tls;
    if (code == FC_OK && options->port_file)
        code = write_port_file(options->port_file, first_tcp_port(s->listeners, s->count), err);
    if (code == FC_OK)
        code = start_web(options, log, s, err);
    return code;
}

/* "127.0.0.1:7450, unix:/run/fc.sock" for the service manager's status line. */
static void describe_listeners(const fc_listener *listeners, size_t count, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (size_t i = 0; i < count && used < size; i++)
        used += (size_t)snprintf(out + used, size - used, "%s%s", i ? ", " : "", listeners[i].address);
}

/* Tells the service manager the daemon is ready: only once the GL context
 * exists and every listener accepts, so a client started after it (After=)
 * finds the daemon answering. */
static void announce_ready(const fc_daemon_context *ctx, const fc_listener *listeners, size_t count,
                           const fc_web_server *web)
{
    char where[512];
    for (size_t i = 0; i < count; i++)
        fc_log_write(ctx->log, FC_LOG_INFO, "listening on %s%s", listeners[i].address,
                     listeners[i].tls ? " (TLS)" : "");
    if (web)
        /* Tests read this line for the web port. */
        fc_log_write(ctx->log, FC_LOG_INFO, "web viewer on %s://%s/", fc_web_server_scheme(web),
                     fc_web_server_address(web));
    describe_listeners(listeners, count, where, sizeof where);
    fc_service_notify(ctx->log, "READY=1\nSTATUS=serving on %s; renderer %s", where, ctx->welcome.renderer);
}

/* Listens, announces the port and serves until a stop signal, then answers
 * what is in flight. /readyz says ready only in between. */
static int serve(const fc_daemon_options *options, fc_daemon_context *ctx, daemon_sockets *s, int stop_fd)
{
    fc_error err;
    fc_event_loop *loop = NULL;
    fc_code code = open_listeners(options, ctx->log, s, &err);
    if (code == FC_OK)
        code = fc_event_loop_create(s->served, s->served_count, stop_fd, s->reload_fd, ctx, &loop, &err);
    if (code == FC_OK) {
        announce_ready(ctx, s->listeners, s->count, s->web);
        fc_metrics_set_phase(ctx->metrics, FC_PHASE_SERVING);
        code = fc_event_loop_run(loop, &err);
    }
    if (code == FC_OK) {
        fc_metrics_set_phase(ctx->metrics, FC_PHASE_DRAINING);
        fc_log_write(ctx->log, FC_LOG_INFO, "%s received: stopping", received_signal_name(stop_fd));
        fc_service_notify(ctx->log, "STOPPING=1\nSTATUS=stopping: answering the renders in flight");
        code = fc_event_loop_drain(loop, &err);
    }
    if (code != FC_OK) {
        fc_log_write(ctx->log, FC_LOG_ERROR, "%s", err.message);
        fc_service_notify(ctx->log, "STATUS=failed: %s", err.message);
    }
    fc_event_loop_destroy(loop);
    return code == FC_OK ? 0 : EXIT_FAILURE;
}

/* Test hook, in the manner of SQLite's test controls: FLUIDCASTD_TEST_LOSE_CONTEXT=N
 * makes the N-th render report a lost GPU context, so the tests can drive the
 * real recovery on drivers that never lose one (llvmpipe). Read here once and
 * passed down; deliberately absent from --help. *render 0 when unset. */
static fc_code read_test_hooks(uint64_t *lose_context_at_render, fc_error *err)
{
    const char *text = getenv("FLUIDCASTD_TEST_LOSE_CONTEXT");
    *lose_context_at_render = 0;
    if (!text)
        return FC_OK;
    char *end = NULL;
    errno = 0;
    unsigned long long n = strtoull(text, &end, 10);
    if (text[0] < '1' || text[0] > '9' || *end != '\0' || errno == ERANGE)
        return fc_error_set(err, FC_ERR_USAGE, "FLUIDCASTD_TEST_LOSE_CONTEXT '%s': expected a whole number >= 1",
                            text);
    *lose_context_at_render = n;
    return FC_OK;
}

/* Each line of what choosing the GPU passed over, as a warning: an operator
 * who asked for a GPU and got llvmpipe must see why in the first lines. */
static void log_gpu_notes(const fc_log *log, const char *notes)
{
    while (notes && *notes) {
        const char *end = strchr(notes, '\n');
        int length = end ? (int)(end - notes) : (int)strlen(notes);
        fc_log_write(log, FC_LOG_WARN, "%.*s", length, notes);
        notes = end ? end + 1 : NULL;
    }
}

static int run_render_service(const fc_daemon_options *options, const fc_auth_token *token, const fc_log *log,
                              uint64_t lose_context_at_render, fc_metrics *metrics, daemon_sockets *s, int stop_fd)
{
    fc_error err;
    fc_render_service *render = NULL;
    fc_render_service_config config = {
        .gpu = options->gpu,
        .shader_dir = options->shader_dir,
        .encoders = options->encoders ? options->encoders : fc_encoder_pool_default_threads(),
        .png_compression = options->png_compression,
        .log = log,
        .lose_context_at_render = lose_context_at_render,
        .metrics = metrics,
    };
    fc_service_notify(log, "STATUS=starting: creating the OpenGL context");
    if (fc_render_service_create(&config, &render, &err) != FC_OK) {
        fc_log_write(log, FC_LOG_ERROR, "cannot render: %s", err.message);
        fc_service_notify(log, "STATUS=failed: cannot render: %s", err.message);
        fc_log_write(log, FC_LOG_ERROR,
                     "fluidcastd needs an OpenGL 4.5 core context through EGL: a GPU driver, or Mesa's "
                     "llvmpipe with --gpu software");
        return EXIT_FAILURE;
    }
    log_gpu_notes(log, fc_render_service_gpu_notes(render));
    fc_log_write(log, FC_LOG_INFO, "GPU: %s", fc_render_service_device(render));
    fc_log_write(log, FC_LOG_INFO, "EGL vendor: %s", fc_render_service_egl_vendor(render));
    fc_log_write(log, FC_LOG_INFO, "GL_RENDERER: %s", fc_render_service_renderer(render));
    fc_log_write(log, FC_LOG_INFO, "GL_VERSION: %s", fc_render_service_gl_version(render));
    fc_log_write(log, FC_LOG_INFO, "GL context: %s",
                 fc_render_service_robust(render) ? "robust (a GPU reset is noticed and recovered from)"
                                                  : "not robust (the driver refused reset notification)");
    if (lose_context_at_render)
        fc_log_write(log, FC_LOG_WARN, "test hook: render %llu will report a lost GPU context",
                     (unsigned long long)lose_context_at_render);
    fc_log_write(log, FC_LOG_INFO, "%u encoder thread(s)", config.encoders);
    fc_daemon_context ctx = {
        .log = log,
        .render = render,
        .chunk_timeout_ms = options->chunk_timeout_ms,
        .refresh_ms = options->refresh_ms,
        .token = token,
        .max_connections = options->max_connections,
        .idle_timeout_ms = options->idle_timeout_ms,
        .read_timeout_ms = options->read_timeout_ms,
        .tls_handshake_timeout_ms = options->tls_handshake_timeout_ms,
        .max_session_memory = options->max_session_memory,
        .metrics = metrics,
    };
    fill_welcome(options, render, &ctx.welcome);
    fc_metrics_set_build_info(metrics, FLUIDCASTD_VERSION, ctx.welcome.renderer, ctx.welcome.device);
    int status = EXIT_FAILURE;
    if (fc_frame_pool_create(FRAME_POOL_BLOCKS, FRAME_POOL_BYTES, &ctx.frames, &err) == FC_OK &&
        fc_registry_create(options->max_sessions, ctx.frames, &ctx.sessions, &err) == FC_OK)
        status = serve(options, &ctx, s, stop_fd);
    else
        fc_log_write(log, FC_LOG_ERROR, "%s", err.message);
    fc_registry_destroy(ctx.sessions);
    fc_render_service_destroy(render);
    if (ctx.frames)
        /* Tests read this line: it stays flat while a stream of same-sized frames goes on. */
        fc_log_write(log, FC_LOG_INFO, "frame blocks allocated: %llu",
                     (unsigned long long)fc_frame_pool_allocations(ctx.frames));
    fc_frame_pool_destroy(ctx.frames);
    return status;
}

/* The metrics and the sockets, which exist before the GL context, around the
 * render service and the event loop. */
static int run(const fc_daemon_options *options, const fc_auth_token *token, const fc_log *log,
               uint64_t lose_context_at_render, fc_tls_server *tls, int stop_fd, int reload_fd)
{
    fc_error err;
    fc_metrics *metrics = NULL;
    daemon_sockets sockets = {.metrics_fd = -1, .tls = tls, .reload_fd = reload_fd};
    int status = EXIT_FAILURE;
    if (fc_metrics_create(&metrics, &err) == FC_OK && inherit_sockets(options, log, &sockets, &err) == FC_OK &&
        start_metrics(options, log, metrics, &sockets, &err) == FC_OK)
        status = run_render_service(options, token, log, lose_context_at_render, metrics, &sockets, stop_fd);
    else
        fc_log_write(log, FC_LOG_ERROR, "cannot start: %s", err.message);
    close_sockets(&sockets);
    fc_metrics_destroy(metrics);
    return status;
}

int main(int argc, char **argv)
{
    fc_daemon_options options;
    fc_error err;
    if (fc_daemon_options_default(&options, &err) != FC_OK ||
        fc_daemon_options_parse(argc, argv, &options, &err) != FC_OK) {
        fprintf(stderr, "fluidcastd: %s\n", err.message);
        return EXIT_BAD_USAGE;
    }
    if (options.help) {
        fc_daemon_options_print_help(stdout, argv[0]);
        return 0;
    }
    fc_log log = {options.log_level};
    fc_auth_token token;
    if (fc_auth_token_load(options.token_file, getenv("FLUIDCAST_TOKEN"), &token, &err) != FC_OK) {
        fprintf(stderr, "fluidcastd: %s\n", err.message);
        return err.code == FC_ERR_USAGE ? EXIT_BAD_USAGE : EXIT_FAILURE;
    }
    uint64_t lose_context_at_render;
    if (read_test_hooks(&lose_context_at_render, &err) != FC_OK) {
        fprintf(stderr, "fluidcastd: %s\n", err.message);
        return EXIT_BAD_USAGE;
    }
    fc_tls_server *tls = NULL;
    fc_tls_server_files tls_files = {options.tls_cert, options.tls_key, options.tls_client_ca};
    if (options.tls_cert && fc_tls_server_create(&tls_files, &tls, &err) != FC_OK) {
        fprintf(stderr, "fluidcastd: %s\n", err.message);
        return err.code == FC_ERR_USAGE ? EXIT_BAD_USAGE : EXIT_FAILURE;
    }
    warn_if_open(&options, &token, &log);
    warn_if_clear(&options, &log);
    /* A client that disconnects mid-reply must cost an EPIPE, not the process. */
    signal(SIGPIPE, SIG_IGN);
    int stop_fd = open_signals(SIGINT, SIGTERM, &err);
    int reload_fd = stop_fd < 0 ? -1 : open_signals(SIGHUP, 0, &err);
    int status = EXIT_FAILURE;
    if (reload_fd >= 0)
        status = run(&options, &token, &log, lose_context_at_render, tls, stop_fd, reload_fd);
    else
        fc_log_write(&log, FC_LOG_ERROR, "%s", err.message);
    if (stop_fd >= 0)
        close(stop_fd);
    if (reload_fd >= 0)
        close(reload_fd);
    fc_tls_server_destroy(tls);
    return status;
}
