/* event_loop.c — poll() over the stop fd, the reload fd, the render results,
 * the listeners and the connections. */
#include "net/event_loop.h"

#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fc_error.h"
#include "monotonic.h"
#include "net/connection.h"

enum {
    STOP_SLOT = 0,
    RESULTS_SLOT = 1,
    RELOAD_SLOT = 2,
    FIRST_LISTENER_SLOT = 3,
    ACCEPTS_PER_WAKE = 16,
    /* After running out of descriptors, accepting is retried this much later
     * instead of spinning on a listener that stays readable. */
    ACCEPT_RETRY_MS = 500,
    /* On a stop signal, renders already in flight get this long to be answered;
     * bounded so a client that never reads cannot hold the shutdown. */
    SHUTDOWN_DRAIN_MS = 5000
};

struct fc_event_loop {
    const fc_listener *listeners;
    size_t listener_count;
    int stop_fd;
    int reload_fd;
    fc_daemon_context *ctx;
    fc_connection **connections;
    size_t count;
    size_t capacity;
    struct pollfd *fds;          /* first_connection_slot + capacity entries */
    size_t first_connection_slot;
    double accept_resume_ms;     /* accepting is paused until then */
    uint64_t last_connection_id;
};

fc_code fc_event_loop_create(const fc_listener *listeners, size_t count, int stop_fd, int reload_fd,
                             fc_daemon_context *ctx, fc_event_loop **out, fc_error *err)
{
    fc_event_loop *loop = calloc(1, sizeof *loop);
    if (!loop)
        return fc_error_set(err, FC_ERR_NOMEM, "event loop: out of memory");
    loop->listeners = listeners;
    loop->listener_count = count;
    loop->stop_fd = stop_fd;
    loop->reload_fd = reload_fd;
    loop->ctx = ctx;
    loop->first_connection_slot = FIRST_LISTENER_SLOT + count;
    loop->fds = calloc(loop->first_connection_slot, sizeof *loop->fds);
    if (!loop->fds) {
        free(loop);
        return fc_error_set(err, FC_ERR_NOMEM, "event loop: out of memory");
    }
    *out = loop;
    return FC_OK;
}

void fc_event_loop_destroy(fc_event_loop *loop)
{
    if (!loop)
        return;
    for (size_t i = 0; i < loop->count; i++)
        fc_connection_destroy(loop->connections[i]);
    free(loop->connections);
    free(loop->fds);
    free(loop);
}

static bool grow(fc_event_loop *loop)
{
    size_t capacity = loop->capacity ? loop->capacity * 2 : 16;
    fc_connection **connections = realloc(loop->connections, capacity * sizeof *connections);
    if (!connections)
        return false;
    loop->connections = connections;
    struct pollfd *fds = realloc(loop->fds, (loop->first_connection_slot + capacity) * sizeof *fds);
    if (!fds)
        return false;
    loop->fds = fds;
    loop->capacity = capacity;
    return true;
}

/* Non-blocking, close-on-exec, and (TCP) no Nagle delay: every reply is
 * written whole, so waiting to coalesce only adds latency. */
static bool configure_client_socket(int fd, bool is_unix)
{
    int on = 1;
    int flags = fcntl(fd, F_GETFL);
    return flags >= 0 && fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0 && fcntl(fd, F_SETFD, FD_CLOEXEC) == 0 &&
           (is_unix || setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on) == 0);
}

static void add_client(fc_event_loop *loop, const fc_listener *listener, int fd,
                       const struct sockaddr_storage *addr)
{
    uint64_t id = ++loop->last_connection_id;
    char peer[80];
    if (listener->is_unix)
        snprintf(peer, sizeof peer, "unix#%llu", (unsigned long long)id);
    else
        fc_format_sockaddr(addr, peer, sizeof peer);
    fc_error err;
    fc_connection *c;
    if (!configure_client_socket(fd, listener->is_unix)) {
        fc_log_write(loop->ctx->log, FC_LOG_WARN, "%s: cannot configure the socket: %s", peer, strerror(errno));
        close(fd);
        return;
    }
    if (loop->count == loop->capacity && !grow(loop)) {
        fc_log_write(loop->ctx->log, FC_LOG_WARN, "%s: refused: out of memory", peer);
        close(fd);
        return;
    }
    if (fc_connection_create(fd, peer, id, listener->tls, loop->ctx, &c, &err) != FC_OK) {
        fc_log_write(loop->ctx->log, FC_LOG_WARN, "%s", err.message);
        return;
    }
    /* Refused connections still take a slot until their ERROR is out, so a
     * flood of them is bounded by the accept rate and the linger time. */
    bool over_limit = loop->count >= loop->ctx->max_connections;
    loop->connections[loop->count++] = c;
    fc_metrics_add(loop->ctx->metrics, FC_METRIC_CONNECTIONS_ACCEPTED, 1);
    fc_log_write(loop->ctx->log, FC_LOG_INFO, "%s: connected", peer);
    if (over_limit)
        fc_connection_refuse(c, loop->ctx);
}

static void accept_clients(fc_event_loop *loop, const fc_listener *listener)
{
    for (int i = 0; i < ACCEPTS_PER_WAKE; i++) {
        struct sockaddr_storage addr;
        socklen_t len = sizeof addr;
        int fd = accept(listener->fd, (struct sockaddr *)&addr, &len);
        if (fd >= 0) {
            add_client(loop, listener, fd, &addr);
        } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
            return;
        } else if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
            fc_log_write(loop->ctx->log, FC_LOG_WARN, "accept: %s; retrying in %d ms", strerror(errno),
                         ACCEPT_RETRY_MS);
            loop->accept_resume_ms = fc_monotonic_ms() + ACCEPT_RETRY_MS;
            return;
        }
        /* Anything else (a client that reset before we accepted it) concerns that client only. */
    }
}

static int min_timeout(int a, int b)
{
    if (a < 0)
        return b;
    if (b < 0)
        return a;
    return a < b ? a : b;
}

static int ms_until(double deadline_ms, double now_ms)
{
    if (deadline_ms < 0.0)
        return -1;
    return deadline_ms > now_ms ? (int)(deadline_ms - now_ms) + 1 : 0;
}

/* Fills the pollfd set; returns poll()'s timeout in milliseconds (-1: none). */
static int prepare_poll(fc_event_loop *loop, double now_ms)
{
    int timeout = ms_until(fc_registry_next_deadline(loop->ctx->sessions), now_ms);
    loop->fds[STOP_SLOT] = (struct pollfd){.fd = loop->stop_fd, .events = POLLIN};
    loop->fds[RESULTS_SLOT] = (struct pollfd){.fd = fc_render_service_wake_fd(loop->ctx->render), .events = POLLIN};
    loop->fds[RELOAD_SLOT] = (struct pollfd){.fd = loop->reload_fd, .events = POLLIN};
    bool accepting = now_ms >= loop->accept_resume_ms;
    if (!accepting)
        timeout = min_timeout(timeout, ms_until(loop->accept_resume_ms, now_ms));
    for (size_t i = 0; i < loop->listener_count; i++)
        /* A negative fd makes poll() skip a listener while accepting is paused. */
        loop->fds[FIRST_LISTENER_SLOT + i] =
            (struct pollfd){.fd = accepting ? loop->listeners[i].fd : -1, .events = POLLIN};
    for (size_t i = 0; i < loop->count; i++) {
        const fc_connection *c = loop->connections[i];
        loop->fds[loop->first_connection_slot + i] =
            (struct pollfd){.fd = c->transport.fd, .events = fc_connection_wanted_events(c)};
        timeout = min_timeout(timeout, fc_connection_timeout_ms(c, now_ms));
    }
    return timeout;
}

static fc_connection *find_connection(const fc_event_loop *loop, uint64_t id)
{
    for (size_t i = 0; i < loop->count; i++)
        if (loop->connections[i]->id == id)
            return loop->connections[i];
    return NULL;
}

/* A finished job in the metrics: its render and encode times, or why its
 * image goes nowhere. */
static void count_job(fc_metrics *metrics, const fc_render_job *job, bool delivered)
{
    if (job->error.code != FC_OK) {
        fc_metrics_add(metrics, FC_METRIC_DROPPED_RENDER_FAILED, 1);
        return;
    }
    double render_ms = 0.0;
    for (int s = FC_STAGE_UPLOAD; s <= FC_STAGE_READBACK; s++)
        render_ms += job->stage_ms[s] > 0.0f ? job->stage_ms[s] : 0.0;
    fc_metrics_add(metrics, FC_METRIC_FRAMES_RENDERED, 1);
    fc_metrics_observe(metrics, FC_METRIC_RENDER_SECONDS, render_ms / 1e3);
    fc_metrics_observe(metrics, FC_METRIC_ENCODE_SECONDS, job->stage_ms[FC_STAGE_ENCODE] / 1e3);
    if (!delivered)
        fc_metrics_add(metrics, FC_METRIC_DROPPED_CLIENT_GONE, 1);
}

/* Hands each finished render job to its connection; jobs of connections that
 * have gone meanwhile are dropped. */
static void deliver_results(fc_event_loop *loop)
{
    fc_render_job *job = fc_render_service_collect(loop->ctx->render);
    while (job) {
        fc_render_job *next = job->next;
        fc_connection *c = find_connection(loop, job->connection_id);
        count_job(loop->ctx->metrics, job, c != NULL);
        if (c)
            fc_connection_on_job_done(c, job);
        fc_render_job_free(job);
        job = next;
    }
}

static void service_connections(fc_event_loop *loop, double now_ms)
{
    for (size_t i = 0; i < loop->count; i++) {
        fc_connection *c = loop->connections[i];
        short revents = loop->fds[loop->first_connection_slot + i].revents;
        if (revents || fc_connection_timeout_ms(c, now_ms) == 0)
            fc_connection_on_events(c, revents, loop->ctx);
    }
}

static void remove_finished(fc_event_loop *loop)
{
    size_t kept = 0;
    for (size_t i = 0; i < loop->count; i++) {
        fc_connection *c = loop->connections[i];
        if (!fc_connection_done(c)) {
            loop->connections[kept++] = c;
            continue;
        }
        fc_log_write(loop->ctx->log, FC_LOG_INFO, "%s: closed after %lu message(s)", c->peer, c->messages);
        fc_connection_destroy(c);
    }
    loop->count = kept;
}

static void accept_ready(fc_event_loop *loop)
{
    for (size_t i = 0; i < loop->listener_count; i++)
        if (loop->fds[FIRST_LISTENER_SLOT + i].revents & POLLIN)
            accept_clients(loop, &loop->listeners[i]);
}

/* SIGHUP: every TLS listener reads its certificate and key again. New
 * connections get the new ones; open connections keep the session they have.
 * A file that does not load leaves that listener as it was. */
static void reload_certificates(fc_event_loop *loop)
{
    struct signalfd_siginfo info;
    while (read(loop->reload_fd, &info, sizeof info) == (ssize_t)sizeof info)
        ;   /* several SIGHUPs at once are one reload */
    for (size_t i = 0; i < loop->listener_count; i++) {
        const fc_listener *l = &loop->listeners[i];
        fc_error err;
        if (!l->tls)
            continue;
        if (fc_tls_server_reload(l->tls, &err) == FC_OK)
            fc_log_write(loop->ctx->log, FC_LOG_INFO, "%s: TLS certificate and key reloaded", l->address);
        else
            fc_log_write(loop->ctx->log, FC_LOG_ERROR, "%s: TLS reload failed, keeping the previous certificate: %s",
                         l->address, err.message);
    }
}

/* The loop's state the metrics endpoint's thread cannot read itself. */
static void publish_gauges(fc_event_loop *loop)
{
    fc_metrics_set(loop->ctx->metrics, FC_METRIC_CONNECTIONS, (int64_t)loop->count);
    fc_metrics_set(loop->ctx->metrics, FC_METRIC_SESSIONS, (int64_t)fc_registry_count(loop->ctx->sessions));
}

/* A connection whose RENDER is being rendered, or whose replies are not all sent. */
static bool connection_busy(const fc_connection *c)
{
    return c->phase == FC_CONN_OPEN && (c->conversation.reply_pending || fc_connection_wanted_events(c) == POLLOUT);
}

/* Prepares a drain round: only busy connections are polled, so no new request
 * is read; the stop fd and the listeners are left out (the signal stays
 * readable for the log). Returns how many connections are busy. */
static size_t prepare_drain_poll(fc_event_loop *loop)
{
    size_t busy = 0;
    loop->fds[STOP_SLOT] = (struct pollfd){.fd = -1};
    loop->fds[RELOAD_SLOT] = (struct pollfd){.fd = -1};
    loop->fds[RESULTS_SLOT] = (struct pollfd){.fd = fc_render_service_wake_fd(loop->ctx->render), .events = POLLIN};
    for (size_t i = 0; i < loop->listener_count; i++)
        loop->fds[FIRST_LISTENER_SLOT + i] = (struct pollfd){.fd = -1};
    for (size_t i = 0; i < loop->count; i++) {
        const fc_connection *c = loop->connections[i];
        bool waiting = connection_busy(c);
        busy += waiting;
        loop->fds[loop->first_connection_slot + i] =
            (struct pollfd){.fd = waiting ? c->transport.fd : -1, .events = fc_connection_wanted_events(c)};
    }
    return busy;
}

fc_code fc_event_loop_drain(fc_event_loop *loop, fc_error *err)
{
    double deadline_ms = fc_monotonic_ms() + SHUTDOWN_DRAIN_MS;
    for (;;) {
        double now_ms = fc_monotonic_ms();
        if (prepare_drain_poll(loop) == 0 || now_ms >= deadline_ms)
            return FC_OK;
        if (poll(loop->fds, loop->first_connection_slot + loop->count, ms_until(deadline_ms, now_ms)) < 0) {
            if (errno == EINTR)
                continue;
            return fc_error_set(err, FC_ERR_IO, "poll: %s", strerror(errno));
        }
        if (loop->fds[RESULTS_SLOT].revents)
            deliver_results(loop);
        service_connections(loop, fc_monotonic_ms());
        remove_finished(loop);
        publish_gauges(loop);
    }
}

fc_code fc_event_loop_run(fc_event_loop *loop, fc_error *err)
{
    for (;;) {
        int timeout = prepare_poll(loop, fc_monotonic_ms());
        if (poll(loop->fds, loop->first_connection_slot + loop->count, timeout) < 0) {
            if (errno == EINTR)
                continue;
            return fc_error_set(err, FC_ERR_IO, "poll: %s", strerror(errno));
        }
        if (loop->fds[STOP_SLOT].revents)
            return FC_OK;
        if (loop->fds[RELOAD_SLOT].revents)
            reload_certificates(loop);
        if (loop->fds[RESULTS_SLOT].revents)
            deliver_results(loop);
        fc_registry_expire(loop->ctx->sessions, fc_monotonic_ms());
        /* Connections before accepting: accepting appends to the array the pollfds mirror. */
        service_connections(loop, fc_monotonic_ms());
        remove_finished(loop);
        fc_registry_collect(loop->ctx->sessions);
        accept_ready(loop);
        publish_gauges(loop);
    }
}
