/* channel.c — see channel.h. */
#define _POSIX_C_SOURCE 200809L
#include "channel.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include "socket_io.h"
#include "tls_client.h"

/* OpenSSL writes with write(), which raises SIGPIPE when the server has gone;
 * in clear send() says MSG_NOSIGNAL. So around every TLS call SIGPIPE is
 * blocked on this thread, and one it raised is taken back before unblocking:
 * a vanished server stays an error value, never a signal that kills the
 * simulation hosting the library (the way libpq does it). */
typedef struct sigpipe_guard {
    sigset_t previous;
    bool already_pending;   /* the program's own SIGPIPE, left for it */
} sigpipe_guard;

static void sigpipe_set(sigset_t *set)
{
    sigemptyset(set);
    sigaddset(set, SIGPIPE);
}

static void sigpipe_block(sigpipe_guard *g)
{
    sigset_t pipe_only, pending;
    sigpipe_set(&pipe_only);
    sigpending(&pending);
    g->already_pending = sigismember(&pending, SIGPIPE) == 1;
    pthread_sigmask(SIG_BLOCK, &pipe_only, &g->previous);
}

static void sigpipe_restore(const sigpipe_guard *g)
{
    sigset_t pipe_only, pending;
    sigpipe_set(&pipe_only);
    if (!g->already_pending && sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1) {
        const struct timespec now = {0, 0};
        while (sigtimedwait(&pipe_only, NULL, &now) < 0 && errno == EINTR)
            ;
    }
    pthread_sigmask(SIG_SETMASK, &g->previous, NULL);
}

fc_code fc_channel_start_tls(fc_channel *ch, const char *host, const fc_connect_options *opt, fc_error *err)
{
    sigpipe_guard guard;
    sigpipe_block(&guard);
    fc_code code = fc_tls_client_start(ch->fd, host, opt, &ch->ssl, err);
    sigpipe_restore(&guard);
    return code;
}

static fc_code tls_send(fc_channel *ch, const uint8_t *data, size_t n, fc_error *err)
{
    while (n > 0) {
        size_t sent = 0;
        errno = 0;
        int ret = SSL_write_ex(ch->ssl, data, n, &sent);
        if (ret != 1)
            return fc_tls_client_failure(ch->ssl, ret, "sending to", err);
        data += sent;
        n -= sent;
    }
    return FC_OK;
}

fc_code fc_channel_send_all(fc_channel *ch, const uint8_t *data, size_t n, fc_error *err)
{
    if (!ch->ssl)
        return fc_socket_send_all(ch->fd, data, n, err);
    sigpipe_guard guard;
    sigpipe_block(&guard);
    fc_code code = tls_send(ch, data, n, err);
    sigpipe_restore(&guard);
    return code;
}

/* Over TLS each part is written on its own: every record is encrypted from
 * the part where it lies, so nothing is concatenated either way. */
fc_code fc_channel_send_parts(fc_channel *ch, struct iovec *parts, size_t count, fc_error *err)
{
    if (!ch->ssl)
        return fc_socket_send_parts(ch->fd, parts, count, err);
    sigpipe_guard guard;
    sigpipe_block(&guard);
    fc_code code = FC_OK;
    for (size_t i = 0; i < count && code == FC_OK; i++)
        code = tls_send(ch, parts[i].iov_base, parts[i].iov_len, err);
    sigpipe_restore(&guard);
    return code;
}

fc_code fc_channel_recv_exact(fc_channel *ch, uint8_t *data, size_t n, fc_error *err)
{
    if (!ch->ssl)
        return fc_socket_recv_exact(ch->fd, data, n, err);
    /* A read may write too (an alert), so it is guarded like a write. */
    sigpipe_guard guard;
    sigpipe_block(&guard);
    fc_code code = FC_OK;
    while (n > 0 && code == FC_OK) {
        size_t got = 0;
        errno = 0;
        int ret = SSL_read_ex(ch->ssl, data, n, &got);
        if (ret != 1)
            code = fc_tls_client_failure(ch->ssl, ret, "waiting for", err);
        data += got;
        n -= got;
    }
    sigpipe_restore(&guard);
    return code;
}

bool fc_channel_wait_input(const fc_channel *ch, int timeout_ms)
{
    if (ch->ssl && SSL_pending(ch->ssl) > 0)
        return true;
    struct pollfd pfd = {.fd = ch->fd, .events = POLLIN};
    return poll(&pfd, 1, timeout_ms) > 0;
}

void fc_channel_close(fc_channel *ch, bool orderly)
{
    if (ch->ssl && orderly) {
        /* close_notify, best effort; a socket already dead fails it quietly. */
        sigpipe_guard guard;
        sigpipe_block(&guard);
        SSL_shutdown(ch->ssl);
        sigpipe_restore(&guard);
    }
    SSL_free(ch->ssl);
    ch->ssl = NULL;
    if (ch->fd >= 0)
        close(ch->fd);
    ch->fd = -1;
}
