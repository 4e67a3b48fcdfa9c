/* hardening_tls.h — the hostile-input matrix over TLS: the same cases, the
 * same bytes and the same expectations, carried by a TLS connection to a
 * daemon with a certificate (FC_HARDENING_TRANSPORT=tls; ctest's *_tls
 * tests). The test keeps reading and writing a plain descriptor: the end of a
 * socket pair whose other end a relay thread carries through a real TLS
 * session (OpenSSL, TLS 1.3) to the daemon. What the daemon does, the test
 * sees: its replies decrypted, its close as end of file; a half-close of the
 * test's side becomes a TLS close_notify. */
#ifndef FC_HARDENING_TLS_H
#define FC_HARDENING_TLS_H

#include <openssl/ssl.h>
#include <stdbool.h>
#include <stdint.h>

typedef struct hx_tls hx_tls;

/* Whether this run asks for TLS (FC_HARDENING_TRANSPORT=tls). */
bool hx_tls_requested(void);

/* A self-signed certificate for 127.0.0.1 made by `openssl` in a fresh
 * folder, and a client context that trusts it; NULL (after a failed CHECK)
 * when it cannot be made. */
hx_tls *hx_tls_create(void);
/* The daemon's arguments for it: "--tls-cert", PATH, "--tls-key", PATH. */
const char *hx_tls_cert_path(const hx_tls *t);
const char *hx_tls_key_path(const hx_tls *t);
/* Removes the folder and frees the context (relays may still be running:
 * each holds its own reference). */
void hx_tls_destroy(hx_tls *t);

/* A TLS session with the daemon at 127.0.0.1:port, handshake done, on the
 * connected socket *tcp_fd (blocking); NULL (after a failed CHECK) when it
 * fails. For cases that write TLS records of their own. */
SSL *hx_tls_handshake(hx_tls *t, uint16_t port, int *tcp_fd);

/* A plain descriptor relayed through a new TLS session with the daemon; -1
 * (after a failed CHECK) when the handshake fails. */
int hx_tls_connect(hx_tls *t, uint16_t port);
/* The same for a session made by hx_tls_handshake (the relay takes ssl and tcp). */
int hx_tls_relay(SSL *ssl, int tcp);

#endif
