/* tls_server.h — the TLS side of a TCP listener: its certificate, key and
 * (for mutual TLS) the CAs its clients' certificates must chain to, loaded
 * from files into an OpenSSL context; TLS 1.3, with 1.2 as the floor.
 * SIGHUP reloads the files (fc_tls_server_reload): connections accepted
 * afterwards get the new certificate, those already open keep theirs, since
 * every session holds a reference to the context it was made from.
 * Event-loop thread only, but for fc_tls_server_current. */
#ifndef FC_DAEMON_TLS_SERVER_H
#define FC_DAEMON_TLS_SERVER_H

#include <openssl/ssl.h>

#include "fluidcast_types.h"

typedef struct fc_tls_server_files {
    const char *cert_file;        /* PEM certificate chain, the server's first */
    const char *key_file;         /* PEM private key of that certificate */
    const char *client_ca_file;   /* PEM CAs a client certificate must chain to; NULL: none asked for */
} fc_tls_server_files;

typedef struct fc_tls_server fc_tls_server;

/* Loads the files (kept by path for reloads; the strings must outlive the
 * server). FC_ERR_USAGE naming the file and OpenSSL's reason when one cannot
 * be read, or the key does not match the certificate. */
fc_code fc_tls_server_create(const fc_tls_server_files *files, fc_tls_server **out, fc_error *err);
void fc_tls_server_destroy(fc_tls_server *s);

/* Reads the files again; on success new sessions use them, on failure the
 * previous context stays in use and *err says why. */
fc_code fc_tls_server_reload(fc_tls_server *s, fc_error *err);

/* The files it was created from. */
const fc_tls_server_files *fc_tls_server_paths(const fc_tls_server *s);

/* A reference to the context new sessions are made from now (release it with
 * SSL_CTX_free): for the web viewer's thread, which serves the same
 * certificate and sees a reload as the listeners do. Any thread. */
SSL_CTX *fc_tls_server_current(fc_tls_server *s);

/* A server-side session on the connected socket fd (not yet handshaken);
 * NULL when OpenSSL has no memory. */
SSL *fc_tls_server_session(fc_tls_server *s, int fd);

/* OpenSSL's reasons queued on this thread, "; "-separated, into out (and the queue cleared). */
void fc_tls_drain_errors(char *out, size_t size);

#endif
