/* tls_server.c — see tls_server.h. */
#include "net/tls_server.h"

#include <openssl/err.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

struct fc_tls_server {
    fc_tls_server_files files;
    SSL_CTX *ctx;            /* the context new sessions are made from */
    pthread_mutex_t swap;    /* ctx's replacement against another thread's fc_tls_server_current */
};

void fc_tls_drain_errors(char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    unsigned long code;
    while ((code = ERR_get_error()) != 0) {
        if (used + 2 >= size)
            continue;   /* keep draining, so the next caller starts clean */
        char reason[200];
        ERR_error_string_n(code, reason, sizeof reason);
        used += (size_t)snprintf(out + used, size - used, "%s%s", used ? "; " : "", reason);
    }
    if (!out[0])
        snprintf(out, size, "no reason given by OpenSSL");
}

static fc_code load_failure(const char *what, const char *path, fc_error *err)
{
    char reason[200];
    fc_tls_drain_errors(reason, sizeof reason);
    return fc_error_set(err, FC_ERR_USAGE, "%s %s: %s", what, path, reason);
}

/* No session tickets: a client that reconnects does a full handshake, and
 * nothing arrives after the handshake that a reader might mistake for data. */
static void configure_context(SSL_CTX *ctx)
{
    SSL_CTX_set_min_proto_version(ctx, TLS1_2_VERSION);
    SSL_CTX_set_num_tickets(ctx, 0);
    /* A client that closes without close_notify has ended, like a TCP client's
     * EOF; the protocol's GOODBYE says whether it ended in order. */
    SSL_CTX_set_options(ctx, SSL_OP_NO_TICKET | SSL_OP_NO_RENEGOTIATION | SSL_OP_CIPHER_SERVER_PREFERENCE |
                                 SSL_OP_IGNORE_UNEXPECTED_EOF);
    /* The output queue grows and moves between retries of a write, and idle
     * connections should not hold their 34 KB of record buffers. */
    SSL_CTX_set_mode(ctx, SSL_MODE_ENABLE_PARTIAL_WRITE | SSL_MODE_ACCEPT_MOVING_WRITE_BUFFER |
                              SSL_MODE_RELEASE_BUFFERS);
}

static fc_code load_client_ca(SSL_CTX *ctx, const char *path, fc_error *err)
{
    if (SSL_CTX_load_verify_locations(ctx, path, NULL) != 1)
        return load_failure("--tls-client-ca", path, err);
    STACK_OF(X509_NAME) *names = SSL_load_client_CA_file(path);
    if (names)
        SSL_CTX_set_client_CA_list(ctx, names);
    SSL_CTX_set_verify(ctx, SSL_VERIFY_PEER | SSL_VERIFY_FAIL_IF_NO_PEER_CERT, NULL);
    return FC_OK;
}

static fc_code make_context(const fc_tls_server_files *files, SSL_CTX **out, fc_error *err)
{
    SSL_CTX *ctx = SSL_CTX_new(TLS_server_method());
    if (!ctx)
        return fc_error_set(err, FC_ERR_NOMEM, "TLS: cannot create a context");
    configure_context(ctx);
    fc_code code = FC_OK;
    if (SSL_CTX_use_certificate_chain_file(ctx, files->cert_file) != 1)
        code = load_failure("--tls-cert", files->cert_file, err);
    else if (SSL_CTX_use_PrivateKey_file(ctx, files->key_file, SSL_FILETYPE_PEM) != 1)
        code = load_failure("--tls-key", files->key_file, err);
    else if (SSL_CTX_check_private_key(ctx) != 1)
        code = load_failure("--tls-key does not match --tls-cert:", files->key_file, err);
    else if (files->client_ca_file)
        code = load_client_ca(ctx, files->client_ca_file, err);
    if (code != FC_OK) {
        SSL_CTX_free(ctx);
        return code;
    }
    *out = ctx;
    return FC_OK;
}

fc_code fc_tls_server_create(const fc_tls_server_files *files, fc_tls_server **out, fc_error *err)
{
    fc_tls_server *s = calloc(1, sizeof *s);
    if (!s)
        return fc_error_set(err, FC_ERR_NOMEM, "TLS: out of memory");
    s->files = *files;
    fc_code code = make_context(files, &s->ctx, err);
    if (code == FC_OK && pthread_mutex_init(&s->swap, NULL) != 0) {
        SSL_CTX_free(s->ctx);
        code = fc_error_set(err, FC_ERR_NOMEM, "TLS: cannot create a lock");
    }
    if (code != FC_OK) {
        free(s);
        return code;
    }
    *out = s;
    return FC_OK;
}

void fc_tls_server_destroy(fc_tls_server *s)
{
    if (!s)
        return;
    SSL_CTX_free(s->ctx);
    pthread_mutex_destroy(&s->swap);
    free(s);
}

fc_code fc_tls_server_reload(fc_tls_server *s, fc_error *err)
{
    SSL_CTX *fresh = NULL;
    fc_code code = make_context(&s->files, &fresh, err);
    if (code != FC_OK)
        return code;
    /* Open sessions hold their own reference to the old context. */
    pthread_mutex_lock(&s->swap);
    SSL_CTX *old = s->ctx;
    s->ctx = fresh;
    pthread_mutex_unlock(&s->swap);
    SSL_CTX_free(old);
    return FC_OK;
}

const fc_tls_server_files *fc_tls_server_paths(const fc_tls_server *s)
{
    return &s->files;
}

SSL_CTX *fc_tls_server_current(fc_tls_server *s)
{
    pthread_mutex_lock(&s->swap);
    SSL_CTX *ctx = s->ctx;
    SSL_CTX_up_ref(ctx);
    pthread_mutex_unlock(&s->swap);
    return ctx;
}

SSL *fc_tls_server_session(fc_tls_server *s, int fd)
{
    SSL *ssl = SSL_new(s->ctx);
    if (ssl && SSL_set_fd(ssl, fd) != 1) {
        SSL_free(ssl);
        return NULL;
    }
    if (ssl)
        SSL_set_accept_state(ssl);
    return ssl;
}
