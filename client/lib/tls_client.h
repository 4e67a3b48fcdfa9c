/* tls_client.h — the client's side of TLS (PROTOCOL.md 1.2): the handshake
 * on a connected blocking socket, the server's certificate verified against
 * the system's CAs or the caller's, the host name checked and sent (SNI), an
 * optional client certificate; and OpenSSL's failures turned into the codes
 * that name their cause (FC_ERR_TLS_*). Internal to the library. */
#ifndef FC_TLS_CLIENT_H
#define FC_TLS_CLIENT_H

#include <openssl/ssl.h>

#include "fluidcast.h"

/* "tls://": the address prefix that asks for TLS. */
#define FC_TLS_PREFIX "tls://"

/* Runs the handshake on fd (blocking, its timeouts already set) with the
 * server `host` (a name or an IP address, as connected to). *out: the session,
 * which owns nothing of fd. Errors: FC_ERR_TLS_UNKNOWN_CA, _NAME_MISMATCH,
 * _EXPIRED, _PLAINTEXT_PEER, _CLIENT_CERT, FC_ERR_TLS (files that do not
 * load, other handshake failures), FC_ERR_IO on a timeout, FC_ERR_CLOSED. */
fc_code fc_tls_client_start(int fd, const char *host, const fc_connect_options *opt, SSL **out, fc_error *err);

/* The error for an SSL call on ssl that returned ret (<= 0), `what` saying
 * what was under way ("sending to", "waiting for"). */
fc_code fc_tls_client_failure(SSL *ssl, int ret, const char *what, fc_error *err);

#endif
