/* tls_client.c — see tls_client.h. */
#include "tls_client.h"

#include <arpa/inet.h>
#include <errno.h>
#include <openssl/err.h>
#include <openssl/x509v3.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"

/* OpenSSL's queued reasons, "; "-separated; the queue is left empty. */
static void drain_errors(char *out, size_t size)
{
    size_t used = 0;
    unsigned long code;
    out[0] = '\0';
    while ((code = ERR_get_error()) != 0) {
        if (used + 2 >= size)
            continue;
        char reason[160];
        ERR_error_string_n(code, reason, sizeof reason);
        used += (size_t)snprintf(out + used, size - used, "%s%s", used ? "; " : "", reason);
    }
    if (!out[0])
        snprintf(out, size, "no reason given");
}

static fc_code file_failure(const char *what, const char *path, fc_error *err)
{
    char reason[160];
    drain_errors(reason, sizeof reason);
    return fc_error_set(err, FC_ERR_TLS, "TLS: cannot use the %s %s: %s", what, path, reason);
}

static fc_code make_context(const fc_connect_options *opt, SSL_CTX **out, fc_error *err)
{
    SSL_CTX *ctx = SSL_CTX_new(TLS_client_method());
    if (!ctx)
        return fc_error_set(err, FC_ERR_NOMEM, "TLS: cannot create a context");
    SSL_CTX_set_min_proto_version(ctx, TLS1_2_VERSION);
    SSL_CTX_set_verify(ctx, SSL_VERIFY_PEER, NULL);
    SSL_CTX_set_mode(ctx, SSL_MODE_AUTO_RETRY);
    SSL_CTX_set_options(ctx, SSL_OP_IGNORE_UNEXPECTED_EOF);   /* a server's EOF is FC_ERR_CLOSED, as in clear */
    fc_code code = FC_OK;
    if (opt->tls_ca_file ? SSL_CTX_load_verify_locations(ctx, opt->tls_ca_file, NULL) != 1
                         : SSL_CTX_set_default_verify_paths(ctx) != 1)
        code = file_failure("CA file", opt->tls_ca_file ? opt->tls_ca_file : "(the system's store)", err);
    else if (opt->tls_cert_file && SSL_CTX_use_certificate_chain_file(ctx, opt->tls_cert_file) != 1)
        code = file_failure("client certificate", opt->tls_cert_file, err);
    else if (opt->tls_cert_file &&
             SSL_CTX_use_PrivateKey_file(ctx, opt->tls_key_file ? opt->tls_key_file : opt->tls_cert_file,
                                         SSL_FILETYPE_PEM) != 1)
        code = file_failure("client key", opt->tls_key_file ? opt->tls_key_file : opt->tls_cert_file, err);
    else if (!opt->tls_cert_file && opt->tls_key_file)
        code = fc_error_set(err, FC_ERR_USAGE, "a TLS client key without its certificate");
    if (code != FC_OK) {
        SSL_CTX_free(ctx);
        return code;
    }
    *out = ctx;
    return FC_OK;
}

static bool is_ip_address(const char *host)
{
    unsigned char addr[16];
    return inet_pton(AF_INET, host, addr) == 1 || inet_pton(AF_INET6, host, addr) == 1;
}

/* The name the certificate must carry: a DNS name (also sent as SNI) or an IP address. */
static bool expect_host(SSL *ssl, const char *host)
{
    if (is_ip_address(host))
        return X509_VERIFY_PARAM_set1_ip_asc(SSL_get0_param(ssl), host) == 1;
    return SSL_set_tlsext_host_name(ssl, host) == 1 && SSL_set1_host(ssl, host) == 1;
}

/* A certificate the verification refused: which of the causes a user can act on. */
static fc_code verify_failure(long result, fc_error *err)
{
    const char *why = X509_verify_cert_error_string(result);
    switch (result) {
    case X509_V_ERR_HOSTNAME_MISMATCH:
    case X509_V_ERR_IP_ADDRESS_MISMATCH:
        return fc_error_set(err, FC_ERR_TLS_NAME_MISMATCH,
                            "TLS: the server's certificate does not name this host (%s)", why);
    case X509_V_ERR_CERT_HAS_EXPIRED:
    case X509_V_ERR_CERT_NOT_YET_VALID:
        return fc_error_set(err, FC_ERR_TLS_EXPIRED, "TLS: the server's certificate is not valid now (%s)", why);
    case X509_V_ERR_UNABLE_TO_GET_ISSUER_CERT:
    case X509_V_ERR_UNABLE_TO_GET_ISSUER_CERT_LOCALLY:
    case X509_V_ERR_UNABLE_TO_VERIFY_LEAF_SIGNATURE:
    case X509_V_ERR_DEPTH_ZERO_SELF_SIGNED_CERT:
    case X509_V_ERR_SELF_SIGNED_CERT_IN_CHAIN:
        return fc_error_set(err, FC_ERR_TLS_UNKNOWN_CA,
                            "TLS: the server's certificate is not from a trusted CA (%s); give its CA with --tls-ca",
                            why);
    default:
        return fc_error_set(err, FC_ERR_TLS, "TLS: the server's certificate was refused (%s)", why);
    }
}

/* What the server's alert or our record layer said, by OpenSSL's reason code. */
static fc_code protocol_failure(int reason, const char *text, fc_error *err)
{
    switch (reason) {
    case SSL_R_WRONG_VERSION_NUMBER:
    case SSL_R_PACKET_LENGTH_TOO_LONG:
    case SSL_R_RECORD_LENGTH_MISMATCH:
        return fc_error_set(err, FC_ERR_TLS_PLAINTEXT_PEER,
                            "TLS: the server answered without TLS: this port is not a TLS port (%s)", text);
    case SSL_R_TLSV13_ALERT_CERTIFICATE_REQUIRED:
    case SSL_R_SSLV3_ALERT_BAD_CERTIFICATE:
    case SSL_R_TLSV1_ALERT_UNKNOWN_CA:
    case SSL_R_SSLV3_ALERT_CERTIFICATE_EXPIRED:
    case SSL_R_SSLV3_ALERT_CERTIFICATE_UNKNOWN:
    case SSL_R_TLSV1_ALERT_DECRYPT_ERROR:
        return fc_error_set(err, FC_ERR_TLS_CLIENT_CERT,
                            "TLS: the server wants a client certificate it trusts (--tls-cert, --tls-key): %s", text);
    default:
        return fc_error_set(err, FC_ERR_TLS, "TLS: %s", text);
    }
}

fc_code fc_tls_client_failure(SSL *ssl, int ret, const char *what, fc_error *err)
{
    int saved = errno;
    int code = SSL_get_error(ssl, ret);
    long verified = SSL_get_verify_result(ssl);
    int reason = ERR_GET_REASON(ERR_peek_last_error());
    char text[200];
    drain_errors(text, sizeof text);
    if (code == SSL_ERROR_WANT_READ || code == SSL_ERROR_WANT_WRITE)
        return fc_error_set(err, FC_ERR_IO, "timed out %s the server", what);
    if (code == SSL_ERROR_ZERO_RETURN || (code == SSL_ERROR_SYSCALL && (saved == 0 || saved == EPIPE ||
                                                                        saved == ECONNRESET)))
        return fc_error_set(err, FC_ERR_CLOSED, "the server closed the connection");
    if (code == SSL_ERROR_SYSCALL)
        return fc_error_set(err, FC_ERR_IO, "socket failure %s the server: %s", what, strerror(saved));
    if (verified != X509_V_OK)
        return verify_failure(verified, err);
    return protocol_failure(reason, text, err);
}

fc_code fc_tls_client_start(int fd, const char *host, const fc_connect_options *opt, SSL **out, fc_error *err)
{
    *out = NULL;
    ERR_clear_error();
    SSL_CTX *ctx = NULL;
    fc_code code = make_context(opt, &ctx, err);
    if (code != FC_OK)
        return code;
    SSL *ssl = SSL_new(ctx);
    SSL_CTX_free(ctx);   /* the session keeps its own reference */
    if (!ssl)
        return fc_error_set(err, FC_ERR_NOMEM, "TLS: cannot create a session");
    if (SSL_set_fd(ssl, fd) != 1 || !expect_host(ssl, host)) {
        SSL_free(ssl);
        return fc_error_set(err, FC_ERR_TLS, "TLS: cannot set up a session for %s", host);
    }
    errno = 0;
    int ret = SSL_connect(ssl);
    if (ret != 1) {
        code = fc_tls_client_failure(ssl, ret, "shaking hands with", err);
        SSL_free(ssl);
        return code;
    }
    *out = ssl;
    return FC_OK;
}
