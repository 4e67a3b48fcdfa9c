/* channel.h — a client connection's byte stream: the blocking socket itself
 * (socket_io.h), or a TLS session on it (tls_client.h). The requests above
 * send and receive through these calls alone, whichever it is. Internal to
 * the library. */
#ifndef FC_CHANNEL_H
#define FC_CHANNEL_H

#include <openssl/ssl.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/uio.h>

#include "fluidcast.h"

typedef struct fc_channel {
    int fd;      /* -1: none */
    SSL *ssl;    /* NULL: in clear */
} fc_channel;

/* The TLS handshake on the connected socket (fc_tls_client_start); on success
 * the channel speaks TLS. */
fc_code fc_channel_start_tls(fc_channel *ch, const char *host, const fc_connect_options *opt, fc_error *err);

/* As fc_socket_send_all, fc_socket_send_parts and fc_socket_recv_exact (socket_io.h). */
fc_code fc_channel_send_all(fc_channel *ch, const uint8_t *data, size_t n, fc_error *err);
fc_code fc_channel_send_parts(fc_channel *ch, struct iovec *parts, size_t count, fc_error *err);
fc_code fc_channel_recv_exact(fc_channel *ch, uint8_t *data, size_t n, fc_error *err);

/* True when bytes can be read (decrypted ones included), or the peer hung up,
 * within timeout_ms (0: now, without waiting). */
bool fc_channel_wait_input(const fc_channel *ch, int timeout_ms);

/* Frees the TLS session and closes the socket; orderly (the stream is in
 * step, the server reading): after a TLS close_notify, best effort. */
void fc_channel_close(fc_channel *ch, bool orderly);

#endif
