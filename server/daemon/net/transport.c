/* transport.c — see transport.h. */
#include "net/transport.h"

#include <errno.h>
#include <openssl/err.h>
#include <poll.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fc_error.h"

enum { TLS_HANDSHAKE_RECORD = 0x16 };

void fc_transport_plain(fc_transport *t, int fd)
{
    memset(t, 0, sizeof *t);
    t->fd = fd;
}

fc_code fc_transport_tls(fc_transport *t, int fd, fc_tls_server *server, fc_error *err)
{
    fc_transport_plain(t, fd);
    t->ssl = fc_tls_server_session(server, fd);
    if (!t->ssl)
        return fc_error_set(err, FC_ERR_NOMEM, "TLS: no memory for a session");
    t->blocked_on = POLLIN;
    return FC_OK;
}

void fc_transport_close(fc_transport *t)
{
    SSL_free(t->ssl);
    t->ssl = NULL;
    if (t->fd >= 0)
        close(t->fd);
    t->fd = -1;
}

/* The first byte decides: a TLS client opens with a handshake record, a
 * fluidcast client in clear with "FCST". */
static fc_handshake_result peek_first_byte(fc_transport *t, fc_error *why)
{
    unsigned char first;
    ssize_t n = recv(t->fd, &first, 1, MSG_PEEK);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
        return FC_HANDSHAKE_WAITING;
    if (n <= 0) {
        fc_error_set(why, FC_ERR_CLOSED, "closed before the TLS handshake%s%s", n < 0 ? ": " : "",
                     n < 0 ? strerror(errno) : "");
        return FC_HANDSHAKE_FAILED;
    }
    if (first != TLS_HANDSHAKE_RECORD) {
        SSL_free(t->ssl);
        t->ssl = NULL;
        t->blocked_on = 0;
        return FC_HANDSHAKE_PLAINTEXT_PEER;
    }
    t->peeked = true;
    return FC_HANDSHAKE_DONE;
}

/* After an SSL call returned ret <= 0: true with errno EAGAIN when it must
 * wait, and blocked_on the events it waits for beyond `own` (what the caller
 * polls for anyway: POLLIN to read, POLLOUT to write, 0 for the handshake). */
static bool must_wait(fc_transport *t, int ret, short own)
{
    int code = SSL_get_error(t->ssl, ret);
    short needs = code == SSL_ERROR_WANT_READ ? POLLIN : code == SSL_ERROR_WANT_WRITE ? POLLOUT : 0;
    t->blocked_on = (short)(needs & ~own);
    if (needs) {
        errno = EAGAIN;
        return true;
    }
    return false;
}

fc_handshake_result fc_transport_handshake(fc_transport *t, fc_error *why)
{
    if (!t->ssl)
        return FC_HANDSHAKE_DONE;
    if (!t->peeked) {
        fc_handshake_result first = peek_first_byte(t, why);
        if (first != FC_HANDSHAKE_DONE)
            return first;
    }
    ERR_clear_error();
    int ret = SSL_do_handshake(t->ssl);
    if (ret == 1) {
        t->blocked_on = 0;
        return FC_HANDSHAKE_DONE;
    }
    int saved = errno;
    if (must_wait(t, ret, 0))
        return FC_HANDSHAKE_WAITING;
    char reason[200];
    fc_tls_drain_errors(reason, sizeof reason);
    if (SSL_get_error(t->ssl, ret) == SSL_ERROR_SYSCALL)
        snprintf(reason, sizeof reason, "%s", saved ? strerror(saved) : "the client closed the connection");
    fc_error_set(why, FC_ERR_PROTOCOL, "TLS handshake failed: %s", reason);
    /* OpenSSL has sent its alert; after a fatal error the session is good for nothing else. */
    SSL_free(t->ssl);
    t->ssl = NULL;
    t->blocked_on = 0;
    return FC_HANDSHAKE_FAILED;
}

/* A failed SSL_read/SSL_write as recv()/send() would report it. */
static ssize_t as_socket_result(fc_transport *t, int ret, short own)
{
    int saved = errno;
    if (must_wait(t, ret, own))
        return -1;
    int code = SSL_get_error(t->ssl, ret);
    ERR_clear_error();
    if (code == SSL_ERROR_ZERO_RETURN)
        return 0;   /* close_notify: the peer's orderly end */
    if (code == SSL_ERROR_SYSCALL && saved == 0)
        return 0;   /* end of stream without close_notify */
    errno = code == SSL_ERROR_SYSCALL ? saved : EPROTO;
    return -1;
}

ssize_t fc_transport_recv(fc_transport *t, void *data, size_t size)
{
    if (!t->ssl)
        return recv(t->fd, data, size, 0);
    size_t got = 0;
    ERR_clear_error();
    errno = 0;
    int ret = SSL_read_ex(t->ssl, data, size, &got);
    if (ret == 1) {
        t->blocked_on = 0;
        return (ssize_t)got;
    }
    return as_socket_result(t, ret, POLLIN);
}

ssize_t fc_transport_send(fc_transport *t, const void *data, size_t size)
{
    if (!t->ssl)
        return send(t->fd, data, size, MSG_NOSIGNAL);
    size_t sent = 0;
    ERR_clear_error();
    errno = 0;
    int ret = SSL_write_ex(t->ssl, data, size, &sent);
    if (ret == 1) {
        t->blocked_on = 0;
        return (ssize_t)sent;
    }
    return as_socket_result(t, ret, POLLOUT);
}

bool fc_transport_pending(const fc_transport *t)
{
    return t->ssl && SSL_pending(t->ssl) > 0;
}

int fc_transport_shutdown_write(fc_transport *t)
{
    if (t->ssl) {
        ERR_clear_error();
        SSL_shutdown(t->ssl);   /* close_notify, if the socket takes it now */
        ERR_clear_error();
    }
    return shutdown(t->fd, SHUT_WR);
}
