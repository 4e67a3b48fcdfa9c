/* connection.c — one client socket: message framing, reply queue, closing. */
#include "net/connection.h"

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fc_error.h"
#include "monotonic.h"
#include "uploads/frame_pool.h"

enum {
    /* Messages handled per wake-up, so one busy client cannot starve the others. */
    MESSAGES_PER_WAKE = 16,
    /* Payload memory grows with the bytes that actually arrive, not with what
     * the header announces, so an idle client cannot pin the full limit. */
    PAYLOAD_GROWTH_STEP = 1 << 20,
    /* Buffers above this are released after use instead of kept for the next message. */
    KEEP_BUFFER_BYTES = 4 << 20,
    /* How long a closing connection waits for the peer to read our last ERROR. */
    LINGER_MS = 2000,
    DRAIN_READS_PER_WAKE = 64,
    /* How often a viewer held back by the kernel's send queue is looked at again. */
    BACKLOG_POLL_MS = 10
};

fc_code fc_connection_create(int fd, const char *peer, uint64_t id, fc_tls_server *tls, fc_daemon_context *ctx,
                             fc_connection **out, fc_error *err)
{
    fc_connection *c = calloc(1, sizeof *c);
    if (!c) {
        close(fd);
        return fc_error_set(err, FC_ERR_NOMEM, "connection from %s: out of memory", peer);
    }
    c->id = id;
    fc_transport_plain(&c->transport, fd);
    snprintf(c->peer, sizeof c->peer, "%s", peer);
    if (tls && fc_transport_tls(&c->transport, fd, tls, err) != FC_OK) {
        fc_transport_close(&c->transport);
        free(c);
        return err ? err->code : FC_ERR_NOMEM;
    }
    fc_buf_init(&c->out);
    fc_conversation_init(&c->conversation, c->peer, ctx, id, &c->out);
    c->last_message_ms = fc_monotonic_ms();
    if (tls) {
        c->phase = FC_CONN_HANDSHAKE;
        c->handshake_deadline_ms = c->last_message_ms + ctx->tls_handshake_timeout_ms;
        c->conversation.transport_bytes = FC_TLS_SESSION_BYTES;
    }
    *out = c;
    return FC_OK;
}

void fc_connection_destroy(fc_connection *c)
{
    if (!c)
        return;
    fc_transport_close(&c->transport);
    fc_conversation_free(&c->conversation);
    free(c->payload);
    fc_buf_free(&c->out);
    free(c);
}

static bool has_pending_output(const fc_connection *c)
{
    return c->out_sent < c->out.len;
}

/* What the connection itself waits for, before any TLS needs of the other direction. */
static short own_events(const fc_connection *c)
{
    switch (c->phase) {
    case FC_CONN_HANDSHAKE:
        return c->transport.blocked_on;
    case FC_CONN_OPEN:
        /* While replies wait, the client is not read: that is the back-pressure
         * that keeps a client who never reads from growing our queue. While a
         * RENDER is being rendered it is not read either, so replies keep the
         * order of the requests. */
        if (has_pending_output(c))
            return POLLOUT;
        return c->conversation.reply_pending ? 0 : POLLIN;
    case FC_CONN_FLUSHING:
        return POLLOUT;
    case FC_CONN_LINGERING:
        return POLLIN;
    case FC_CONN_DONE:
        break;
    }
    return 0;
}

short fc_connection_wanted_events(const fc_connection *c)
{
    short events = own_events(c);
    /* A TLS read may have to write first, and a write to read (a key update). */
    if (events && (c->phase == FC_CONN_OPEN || c->phase == FC_CONN_FLUSHING))
        events |= c->transport.blocked_on;
    return events;
}

/* Decrypted bytes wait inside the TLS session, where poll() cannot see them. */
static bool input_buffered(const fc_connection *c)
{
    return (own_events(c) & POLLIN) && c->phase == FC_CONN_OPEN && fc_transport_pending(&c->transport);
}

static bool message_in_progress(const fc_connection *c)
{
    return c->header_got > 0 || c->have_header;
}

/* When the client's silence or slowness ends the connection; negative for
 * never. Only while we wait on the client: not while its RENDER renders or
 * our replies wait to be read, and never for a viewer, which only listens. */
static double client_deadline_ms(const fc_connection *c)
{
    const fc_daemon_context *ctx = c->conversation.ctx;
    if (c->phase != FC_CONN_OPEN || has_pending_output(c) || c->conversation.reply_pending)
        return -1.0;
    if (message_in_progress(c))
        return ctx->read_timeout_ms > 0.0 ? c->started_ms + ctx->read_timeout_ms : -1.0;
    if (c->conversation.role == FC_ROLE_VIEWER || ctx->idle_timeout_ms <= 0.0)
        return -1.0;
    return c->last_message_ms + ctx->idle_timeout_ms;
}

static double earliest(double a, double b)
{
    if (a < 0.0)
        return b;
    return b < 0.0 || a < b ? a : b;
}

int fc_connection_timeout_ms(const fc_connection *c, double now_ms)
{
    double deadline = -1.0;
    if (input_buffered(c))
        return 0;
    if (c->phase == FC_CONN_HANDSHAKE)
        deadline = c->handshake_deadline_ms;
    else if (c->phase == FC_CONN_LINGERING)
        deadline = c->linger_deadline_ms;
    else if (c->phase == FC_CONN_OPEN && c->backlog_check_ms > 0.0)
        deadline = c->backlog_check_ms;
    else if (c->phase == FC_CONN_OPEN)
        deadline = fc_conversation_deadline_ms(&c->conversation);
    deadline = earliest(deadline, client_deadline_ms(c));
    if (deadline < 0.0)
        return -1;
    double left = deadline - now_ms;
    return left > 0 ? (int)left + 1 : 0;
}

/* Once everything queued is sent: close at once if the peer is gone, else
 * shut down our side and linger, because closing a socket with unread input
 * sends a reset that can destroy the ERROR the peer has not read yet. */
static void finish_flushing(fc_connection *c)
{
    if (c->peer_closed || fc_transport_shutdown_write(&c->transport) != 0) {
        c->phase = FC_CONN_DONE;
        return;
    }
    c->phase = FC_CONN_LINGERING;
    c->linger_deadline_ms = fc_monotonic_ms() + LINGER_MS;
}

/* Bytes the kernel still holds for the peer (unsent or unacknowledged); 0 when it cannot tell. */
static size_t kernel_backlog(int fd)
{
    int bytes = 0;
    return ioctl(fd, TIOCOUTQ, &bytes) == 0 && bytes > 0 ? (size_t)bytes : 0;
}

/* Our queue is empty. A viewer is told so only once the kernel's queue is low
 * as well: the kernel buffers megabytes on a fast link, and images waiting
 * there would be exactly the stale frames latest-wins is meant to drop. */
static void report_drained(fc_connection *c)
{
    size_t allowance = fc_conversation_backlog_allowance(&c->conversation);
    if (allowance != SIZE_MAX && kernel_backlog(c->transport.fd) > allowance) {
        c->backlog_check_ms = fc_monotonic_ms() + BACKLOG_POLL_MS;
        return;
    }
    c->backlog_check_ms = 0.0;
    fc_conversation_output_drained(&c->conversation);
}

static void flush(fc_connection *c)
{
    while (has_pending_output(c)) {
        ssize_t n = fc_transport_send(&c->transport, c->out.data + c->out_sent, c->out.len - c->out_sent);
        if (n > 0) {
            c->out_sent += (size_t)n;
            fc_metrics_add(c->conversation.ctx->metrics, FC_METRIC_BYTES_SENT, (uint64_t)n);
        } else if (n < 0 && errno == EINTR) {
            continue;
        } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            return;
        } else {
            /* The peer went away: nobody is left to answer. */
            c->phase = FC_CONN_DONE;
            return;
        }
    }
    if (c->out.cap > KEEP_BUFFER_BYTES)
        fc_buf_free(&c->out);
    else
        fc_buf_reset(&c->out);
    c->out_sent = 0;
    if (c->phase == FC_CONN_FLUSHING)
        finish_flushing(c);
    else if (c->phase == FC_CONN_OPEN)
        report_drained(c);
}

static void start_closing(fc_connection *c)
{
    if (c->phase == FC_CONN_OPEN)
        c->phase = FC_CONN_FLUSHING;
    flush(c);
}

static void apply_verdict(fc_connection *c, fc_conversation_verdict verdict)
{
    if (verdict == FC_CONV_ABORT)
        c->phase = FC_CONN_DONE;
    else if (verdict == FC_CONV_CLOSE)
        start_closing(c);
}

/* The error the client gets for err: one that has not authenticated learns
 * nothing but that it must. */
static fc_error error_for_client(const fc_connection *c, const fc_error *err)
{
    fc_error reply = *err;
    if (fc_conversation_unauthenticated(&c->conversation))
        fc_error_set(&reply, FC_ERR_UNAUTHORIZED, "authentication required");
    return reply;
}

static void close_with_error(fc_connection *c, fc_daemon_context *ctx, uint32_t request_id, const fc_error *err)
{
    fc_error reply = error_for_client(c, err);
    apply_verdict(c, fc_conversation_reply_error(ctx, c->peer, request_id, &reply, FC_CONV_CLOSE, &c->out));
}

void fc_connection_refuse(fc_connection *c, fc_daemon_context *ctx)
{
    if (c->phase == FC_CONN_HANDSHAKE) {
        c->refuse_when_open = true;   /* the ERROR can only travel inside TLS */
        return;
    }
    fc_error err;
    fc_error_set(&err, FC_ERR_LIMIT, "the server has its maximum of %u connections", (unsigned)ctx->max_connections);
    apply_verdict(c, fc_conversation_reply_error(ctx, c->peer, 0, &err, FC_CONV_CLOSE, &c->out));
}

/* A client that stopped mid-message or sent nothing for too long gives up its
 * connection, so slow or silent clients cannot hold descriptors and buffers. */
static void enforce_client_deadline(fc_connection *c, fc_daemon_context *ctx, double now_ms)
{
    double deadline = client_deadline_ms(c);
    if (deadline < 0.0 || now_ms < deadline)
        return;
    fc_error err;
    if (message_in_progress(c))
        fc_error_set(&err, FC_ERR_LIMIT, "message not complete within the read timeout of %.0f ms",
                     ctx->read_timeout_ms);
    else
        fc_error_set(&err, FC_ERR_LIMIT, "no message for the idle timeout of %.0f ms", ctx->idle_timeout_ms);
    close_with_error(c, ctx, 0, &err);
}

static void reset_message(fc_connection *c)
{
    c->header_got = 0;
    c->have_header = false;
    c->payload_got = 0;
    fc_error_clear(&c->header_error);
}

static void forget_payload(fc_connection *c)
{
    c->payload = NULL;
    c->payload_cap = 0;
}

/* A whole message is in: hand it to the client (or answer the header fault
 * found earlier) and start on the next one. */
static void deliver(fc_connection *c, fc_daemon_context *ctx)
{
    fc_conversation_verdict verdict;
    if (c->header_error.code != FC_OK) {
        /* Before the handshake any error ends the connection. */
        fc_error reply = error_for_client(c, &c->header_error);
        fc_conversation_verdict then =
            c->conversation.state == FC_CONV_READY ? FC_CONV_CONTINUE : FC_CONV_CLOSE;
        verdict = fc_conversation_reply_error(ctx, c->peer, c->header.request_id, &reply, then, &c->out);
    } else {
        c->conversation.message_started_ms = c->started_ms;
        fc_payload payload = {c->payload, c->payload_cap};
        verdict = fc_conversation_handle(&c->conversation, ctx, &c->header, &payload, fc_monotonic_ms(), &c->out);
        if (!payload.bytes)
            forget_payload(c);   /* a frame decoded in place kept it */
    }
    reset_message(c);
    c->last_message_ms = fc_monotonic_ms();
    if (c->payload_cap > KEEP_BUFFER_BYTES) {
        fc_frame_pool_give(ctx->frames, c->payload, c->payload_cap);
        forget_payload(c);
    }
    c->messages++;
    fc_metrics_add(ctx->metrics, FC_METRIC_MESSAGES_RECEIVED, 1);
    apply_verdict(c, verdict);
    if (c->phase == FC_CONN_OPEN)
        flush(c);
}

/* The 16 header bytes are in. Bad magic or an oversized length leave no way
 * to find the next message: answer and close. Other header faults (flags)
 * still give the length, so the payload is skipped and the error answered. */
static void on_header(fc_connection *c, fc_daemon_context *ctx)
{
    fc_error err;
    fc_code code = fc_wire_decode_header(c->header_bytes, ctx->welcome.limits.max_message, &c->header, &err);
    if (code == FC_ERR_BAD_MAGIC || code == FC_ERR_TOO_LARGE) {
        close_with_error(c, ctx, code == FC_ERR_TOO_LARGE ? c->header.request_id : 0, &err);
        return;
    }
    if (code != FC_OK)
        c->header_error = err;
    c->have_header = true;
    if (c->header.length == 0)
        deliver(c, ctx);
}

/* A pooled block that fits the payload, before any of it arrived: a
 * producer's next frame lands in the block a frame it sent before gave back
 * (up to an eighth larger: compressed payloads vary in size). */
static bool adopt_recycled(fc_connection *c, fc_frame_pool *pool, size_t length)
{
    if (c->payload_got != 0 || length < FC_FRAME_POOL_MIN_BYTES)
        return false;
    size_t size;
    uint8_t *block = fc_frame_pool_reuse_roomy(pool, length, &size);
    if (!block)
        return false;
    fc_frame_pool_give(pool, c->payload, c->payload_cap);
    c->payload = block;
    c->payload_cap = size;
    return true;
}

/* Room for the next bytes of the payload: a recycled block, or grown step by step up to its length. */
static bool reserve_payload(fc_connection *c, fc_frame_pool *pool)
{
    size_t length = c->header.length;
    if (c->payload_cap >= length || adopt_recycled(c, pool, length) || c->payload_cap - c->payload_got > 0)
        return true;
    size_t cap = c->payload_cap * 2 > PAYLOAD_GROWTH_STEP ? c->payload_cap * 2 : PAYLOAD_GROWTH_STEP;
    if (cap > length)
        cap = length;
    uint8_t *grown = realloc(c->payload, cap);
    if (!grown)
        return false;
    c->payload = grown;
    c->payload_cap = cap;
    if (cap == length && length >= FC_FRAME_POOL_MIN_BYTES)
        fc_frame_pool_note_allocation(pool);   /* a new block that may end up in the pool */
    return true;
}

typedef enum read_result {
    READ_PROGRESS,       /* bytes arrived (or the phase changed) */
    READ_WOULD_BLOCK,
    READ_EOF,
    READ_FAILED
} read_result;

static read_result classify_recv(ssize_t n)
{
    if (n > 0 || (n < 0 && errno == EINTR))
        return READ_PROGRESS;
    if (n == 0)
        return READ_EOF;
    return errno == EAGAIN || errno == EWOULDBLOCK ? READ_WOULD_BLOCK : READ_FAILED;
}

static read_result receive_header(fc_connection *c, fc_daemon_context *ctx)
{
    ssize_t n = fc_transport_recv(&c->transport, c->header_bytes + c->header_got, FC_WIRE_HEADER_SIZE - c->header_got);
    if (n > 0)
        fc_metrics_add(ctx->metrics, FC_METRIC_BYTES_RECEIVED, (uint64_t)n);
    if (n > 0 && c->header_got == 0)
        c->started_ms = fc_monotonic_ms();
    if (n > 0 && (c->header_got += (size_t)n) == FC_WIRE_HEADER_SIZE)
        on_header(c, ctx);
    return classify_recv(n);
}

static read_result receive_payload(fc_connection *c, fc_daemon_context *ctx)
{
    if (!reserve_payload(c, ctx->frames)) {
        fc_error err;
        fc_error_set(&err, FC_ERR_INTERNAL, "no memory for a %u-byte payload", (unsigned)c->header.length);
        close_with_error(c, ctx, c->header.request_id, &err);
        return READ_PROGRESS;
    }
    size_t room = c->payload_cap - c->payload_got;
    size_t wanted = c->header.length - c->payload_got;
    ssize_t n = fc_transport_recv(&c->transport, c->payload + c->payload_got, room < wanted ? room : wanted);
    if (n > 0)
        fc_metrics_add(ctx->metrics, FC_METRIC_BYTES_RECEIVED, (uint64_t)n);
    if (n > 0 && (c->payload_got += (size_t)n) == c->header.length)
        deliver(c, ctx);
    return classify_recv(n);
}

static void read_messages(fc_connection *c, fc_daemon_context *ctx)
{
    unsigned long first = c->messages;
    while (c->phase == FC_CONN_OPEN && !has_pending_output(c) && !c->conversation.reply_pending &&
           c->messages - first < MESSAGES_PER_WAKE) {
        read_result result = c->have_header ? receive_payload(c, ctx) : receive_header(c, ctx);
        if (result == READ_WOULD_BLOCK)
            return;
        if (result == READ_EOF) {
            c->peer_closed = true;
            start_closing(c);
        } else if (result == READ_FAILED) {
            c->phase = FC_CONN_DONE;
        }
    }
}

/* Lingering: input is discarded until the peer closes, errs or the deadline passes. */
static void drain_input(fc_connection *c)
{
    uint8_t scratch[4096];
    read_result result = READ_PROGRESS;
    /* Bounded, so a peer that keeps sending cannot hold the loop here. */
    for (int reads = 0; reads < DRAIN_READS_PER_WAKE && result == READ_PROGRESS; reads++)
        result = classify_recv(recv(c->transport.fd, scratch, sizeof scratch, 0));
    if (result == READ_EOF || result == READ_FAILED || fc_monotonic_ms() >= c->linger_deadline_ms)
        c->phase = FC_CONN_DONE;
}

/* A client that speaks in clear to a TLS port learns so in clear, the one
 * answer it can read, and is closed. Not ERROR UNAUTHORIZED even when a
 * token is set: this says nothing about the daemon but that it wants TLS. */
static void refuse_plaintext(fc_connection *c, fc_daemon_context *ctx)
{
    fc_error err;
    fc_error_set(&err, FC_ERR_TLS_REQUIRED, "this port speaks TLS: connect with tls://HOST:PORT (or --tls)");
    fc_log_write(ctx->log, FC_LOG_WARN, "%s: a client without TLS on a TLS port: refused", c->peer);
    fc_metrics_add(ctx->metrics, FC_METRIC_TLS_HANDSHAKE_FAILURES, 1);
    c->conversation.transport_bytes = 0;
    c->phase = FC_CONN_OPEN;
    apply_verdict(c, fc_conversation_reply_error(ctx, c->peer, 0, &err, FC_CONV_CLOSE, &c->out));
}

/* One step of the TLS handshake, or its end: stalled past the handshake
 * timeout, failed, or done (then the conversation starts). */
static void advance_handshake(fc_connection *c, fc_daemon_context *ctx, double now_ms)
{
    fc_error why;
    fc_handshake_result result = fc_transport_handshake(&c->transport, &why);
    if (result == FC_HANDSHAKE_DONE) {
        c->phase = FC_CONN_OPEN;
        c->last_message_ms = now_ms;
        fc_metrics_add(ctx->metrics, FC_METRIC_TLS_HANDSHAKES, 1);
        fc_log_write(ctx->log, FC_LOG_DEBUG, "%s: TLS %s, %s", c->peer, SSL_get_version(c->transport.ssl),
                     SSL_get_cipher_name(c->transport.ssl));
        if (c->refuse_when_open)
            fc_connection_refuse(c, ctx);
        else
            read_messages(c, ctx);   /* the HELLO may have come with the handshake's last flight */
    } else if (result == FC_HANDSHAKE_PLAINTEXT_PEER) {
        refuse_plaintext(c, ctx);
    } else if (result == FC_HANDSHAKE_FAILED) {
        fc_log_write(ctx->log, FC_LOG_WARN, "%s: %s", c->peer, why.message);
        fc_metrics_add(ctx->metrics, FC_METRIC_TLS_HANDSHAKE_FAILURES, 1);
        /* Linger like any closing connection: a TLS 1.3 client may already
         * have sent its HELLO, and closing on it would reset the alert away. */
        c->phase = FC_CONN_FLUSHING;
        c->peer_closed = why.code == FC_ERR_CLOSED;
        finish_flushing(c);
    } else if (now_ms >= c->handshake_deadline_ms) {
        fc_log_write(ctx->log, FC_LOG_INFO, "%s: TLS handshake not complete within %.0f ms: dropped", c->peer,
                     ctx->tls_handshake_timeout_ms);
        fc_metrics_add(ctx->metrics, FC_METRIC_TLS_HANDSHAKE_TIMEOUTS, 1);
        c->phase = FC_CONN_DONE;
    }
}

void fc_connection_on_events(fc_connection *c, short revents, fc_daemon_context *ctx)
{
    if (c->phase == FC_CONN_HANDSHAKE) {
        advance_handshake(c, ctx, fc_monotonic_ms());
        return;
    }
    if (input_buffered(c))
        revents |= POLLIN;
    /* A TLS read that had to wait for a write, or a write for a read, goes on
     * when the socket allows that. */
    if (c->transport.blocked_on & revents)
        revents |= c->transport.blocked_on == POLLIN ? POLLOUT : POLLIN;
    /* A socket error surfaces from send() or recv(), whichever comes first. */
    if (revents & (POLLOUT | POLLHUP | POLLERR))
        flush(c);
    if (c->phase == FC_CONN_OPEN && c->conversation.reply_pending && (revents & (POLLHUP | POLLERR)))
        c->phase = FC_CONN_DONE;   /* reset while its RENDER renders: nobody is left to answer */
    else if (c->phase == FC_CONN_OPEN && (revents & (POLLIN | POLLHUP | POLLERR)))
        read_messages(c, ctx);
    else if (c->phase == FC_CONN_LINGERING)
        drain_input(c);
    enforce_client_deadline(c, ctx, fc_monotonic_ms());
    if (c->phase == FC_CONN_OPEN && revents == 0 && c->backlog_check_ms > 0.0)
        report_drained(c);
    else if (c->phase == FC_CONN_OPEN && revents == 0)
        fc_conversation_tick(&c->conversation, fc_monotonic_ms());
}

void fc_connection_on_job_done(fc_connection *c, const fc_render_job *job)
{
    if (c->phase != FC_CONN_OPEN)
        return;
    fc_conversation_job_done(&c->conversation, job);
    flush(c);
}
