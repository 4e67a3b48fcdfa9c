/* transport.h — how a connection's bytes travel: in clear on the socket, or
 * through a TLS session on it. The connection (connection.c) reads and writes
 * through these calls alone, with recv()/send()'s conventions (a count, 0 at
 * the peer's end, -1 with errno EAGAIN when it must wait), so it does not care
 * which transport it has. A TLS transport first runs its handshake
 * (fc_transport_handshake) without blocking, step by step as poll() reports
 * the socket ready. */
#ifndef FC_DAEMON_TRANSPORT_H
#define FC_DAEMON_TRANSPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "net/tls_server.h"

/* What a TLS session holds besides the connection's own buffers: OpenSSL's
 * state and its record buffers while in use (about 34 KB), counted against
 * the connection's memory limit (conversation_memory.h). */
#define FC_TLS_SESSION_BYTES ((uint64_t)48 << 10)

typedef struct fc_transport {
    int fd;
    SSL *ssl;          /* NULL: plaintext */
    short blocked_on;  /* TLS: what its last call waits for beyond its own direction: the handshake's
                          next event, a read's POLLOUT or a write's POLLIN; 0: nothing more */
    bool peeked;       /* TLS: the first byte was seen to open a TLS handshake */
} fc_transport;

typedef enum fc_handshake_result {
    FC_HANDSHAKE_DONE = 0,
    FC_HANDSHAKE_WAITING,           /* call again when blocked_on is ready */
    FC_HANDSHAKE_PLAINTEXT_PEER,    /* the client spoke without TLS; the transport is plaintext now */
    FC_HANDSHAKE_FAILED             /* *why says why; the alert is sent, the session dropped: close */
} fc_handshake_result;

void fc_transport_plain(fc_transport *t, int fd);
/* A TLS transport on fd from the listener's context; FC_ERR_NOMEM when OpenSSL has none. */
fc_code fc_transport_tls(fc_transport *t, int fd, fc_tls_server *server, fc_error *err);
/* Closes the socket and frees the session. */
void fc_transport_close(fc_transport *t);

/* One step of the TLS handshake. A client whose first byte does not open a
 * TLS record is a plaintext client: reported, and the session dropped so
 * that the caller can answer it in clear. */
fc_handshake_result fc_transport_handshake(fc_transport *t, fc_error *why);

ssize_t fc_transport_recv(fc_transport *t, void *data, size_t size);
ssize_t fc_transport_send(fc_transport *t, const void *data, size_t size);
/* Bytes already decrypted and waiting: poll() does not see them. */
bool fc_transport_pending(const fc_transport *t);
/* Ends our sending side: TLS close_notify (best effort), then shutdown(SHUT_WR). 0 or -1. */
int fc_transport_shutdown_write(fc_transport *t);

static inline bool fc_transport_is_tls(const fc_transport *t)
{
    return t->ssl != NULL;
}

#endif
