/* fluidcastd.c — the render daemon's top level: options, signals, the render
 * service (GL thread and encoders), the named sessions, the listeners and the
 * event loop, in that order; exit 0 on SIGINT/SIGTERM, 1 when it cannot start,
 * 2 on a bad command line. The folders below (net/, clients/, sessions/, gpu/,
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
#include "options.h"
#include "uploads/frame_pool.h"

#define SERVER_VERSION "fluidcastd 0.1.0"

/* EXIT_FAILURE (1): cannot start or keep serving. */
enum { EXIT_BAD_USAGE = 2, MAX_LISTENERS = 2 };

/* What the frame pool may keep waiting between frames: a stream needs about
 * three blocks (the frame being received, the newest, the one being
 * rendered), so a few streams of frames up to tens of megabytes recycle all
 * of theirs; an idle daemon keeps no more than this. */
#define FRAME_POOL_BLOCKS 8
#define FRAME_POOL_BYTES ((size_t)256 << 20)

/* SIGINT/SIGTERM are blocked and read from a signalfd the event loop polls:
 * no handler, no global flag. Blocked before any thread exists (llvmpipe and
 * OpenImageIO start their own), since threads inherit the mask and a thread
 * without it would let the signal kill the process. */
static int open_stop_signals(fc_error *err)
{
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    if (sigprocmask(SIG_BLOCK, &stop, NULL) != 0) {
        fc_error_set(err, FC_ERR_IO, "sigprocmask: %s", strerror(errno));
        return -1;
    }
    int fd = signalfd(-1, &stop, SFD_NONBLOCK | SFD_CLOEXEC);
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

/* Opens the TCP and/or Unix listeners the options ask for; *count of them. */
static fc_code open_listeners(const fc_daemon_options *options, fc_listener *listeners, size_t *count,
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
    if (code == FC_OK && options->port_file)
        code = write_port_file(options->port_file, listeners[0].is_unix ? 0 : listeners[0].port, err);
    return code;
}

/* Listens, announces the port and serves until a stop signal. */
static int serve(const fc_daemon_options *options, fc_daemon_context *ctx, int stop_fd)
{
    fc_error err;
    fc_listener listeners[MAX_LISTENERS];
    size_t count = 0;
    fc_event_loop *loop = NULL;
    fc_code code = open_listeners(options, listeners, &count, &err);
    if (code == FC_OK)
        code = fc_event_loop_create(listeners, count, stop_fd, ctx, &loop, &err);
    if (code == FC_OK) {
        for (size_t i = 0; i < count; i++)
            fc_log_write(ctx->log, FC_LOG_INFO, "listening on %s", listeners[i].address);
        code = fc_event_loop_run(loop, &err);
    }
    if (code == FC_OK)
        fc_log_write(ctx->log, FC_LOG_INFO, "%s received: stopping", received_signal_name(stop_fd));
    else
        fc_log_write(ctx->log, FC_LOG_ERROR, "%s", err.message);
    fc_event_loop_destroy(loop);
    for (size_t i = 0; i < count; i++)
        fc_listener_close(&listeners[i]);
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

static int run(const fc_daemon_options *options, const fc_auth_token *token, const fc_log *log,
               uint64_t lose_context_at_render, int stop_fd)
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
    };
    if (fc_render_service_create(&config, &render, &err) != FC_OK) {
        fc_log_write(log, FC_LOG_ERROR, "cannot render: %s", err.message);
        fc_log_write(log, FC_LOG_ERROR,
                     "fluidcastd needs an OpenGL 4.5 core context through EGL: a GPU driver, or Mesa's "
                     "llvmpipe with --gpu software");
        return EXIT_FAILURE;
    }
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
        .max_session_memory = options->max_session_memory,
    };
    fill_welcome(options, render, &ctx.welcome);
    int status = EXIT_FAILURE;
    if (fc_frame_pool_create(FRAME_POOL_BLOCKS, FRAME_POOL_BYTES, &ctx.frames, &err) == FC_OK &&
        fc_registry_create(options->max_sessions, ctx.frames, &ctx.sessions, &err) == FC_OK)
        status = serve(options, &ctx, stop_fd);
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

int main(int argc, char **argv)
{
    fc_daemon_options options;
    fc_error err;
    fc_daemon_options_default(&options);
    if (fc_daemon_options_parse(argc, argv, &options, &err) != FC_OK) {
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
    warn_if_open(&options, &token, &log);
    /* A client that disconnects mid-reply must cost an EPIPE, not the process. */
    signal(SIGPIPE, SIG_IGN);
    int stop_fd = open_stop_signals(&err);
    if (stop_fd < 0) {
        fc_log_write(&log, FC_LOG_ERROR, "%s", err.message);
        return EXIT_FAILURE;
    }
    int status = run(&options, &token, &log, lose_context_at_render, stop_fd);
    close(stop_fd);
    return status;
}
