/* hardening_tls.c — see hardening_tls.h. */
#include "hardening_tls.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fc_error.h"
#include "test_socket.h"
#include "test_util.h"

struct hx_tls {
    char dir[64];
    char cert[96];
    char key[96];
    SSL_CTX *client;
};

bool hx_tls_requested(void)
{
    const char *transport = getenv("FC_HARDENING_TRANSPORT");
    return transport && strcmp(transport, "tls") == 0;
}

hx_tls *hx_tls_create(void)
{
    hx_tls *t = calloc(1, sizeof *t);
    if (!t) {
        CHECK_MSG(0, "out of memory");
        return NULL;
    }
    snprintf(t->dir, sizeof t->dir, "/tmp/fc_hx_tls_XXXXXX");
    if (!mkdtemp(t->dir)) {
        CHECK_MSG(0, "mkdtemp: %s", strerror(errno));
        free(t);
        return NULL;
    }
    snprintf(t->cert, sizeof t->cert, "%s/server.pem", t->dir);
    snprintf(t->key, sizeof t->key, "%s/server.key", t->dir);
    char command[512];
    snprintf(command, sizeof command,
             "openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -days 1 -subj /CN=localhost "
             "-addext subjectAltName=IP:127.0.0.1 -keyout '%s' -out '%s' 2>/dev/null",
             t->key, t->cert);
    bool made = system(command) == 0;
    t->client = made ? SSL_CTX_new(TLS_client_method()) : NULL;
    if (t->client) {
        SSL_CTX_set_min_proto_version(t->client, TLS1_3_VERSION);
        SSL_CTX_set_verify(t->client, SSL_VERIFY_PEER, NULL);
    }
    if (!t->client || SSL_CTX_load_verify_locations(t->client, t->cert, NULL) != 1) {
        CHECK_MSG(0, "cannot make the test's certificate or trust it (%s)", command);
        hx_tls_destroy(t);
        return NULL;
    }
    return t;
}

const char *hx_tls_cert_path(const hx_tls *t)
{
    return t->cert;
}

const char *hx_tls_key_path(const hx_tls *t)
{
    return t->key;
}

void hx_tls_destroy(hx_tls *t)
{
    if (!t)
        return;
    unlink(t->cert);
    unlink(t->key);
    rmdir(t->dir);
    SSL_CTX_free(t->client);
    free(t);
}

SSL *hx_tls_handshake(hx_tls *t, uint16_t port, int *tcp_fd)
{
    fc_error err;
    if (fc_test_connect(port, tcp_fd, &err) != FC_OK) {
        CHECK_MSG(0, "%s", err.message);
        return NULL;
    }
    SSL *ssl = SSL_new(t->client);
    bool ok = ssl && SSL_set_fd(ssl, *tcp_fd) == 1 && SSL_set1_host(ssl, "127.0.0.1") == 1 && SSL_connect(ssl) == 1;
    if (!ok) {
        CHECK_MSG(0, "TLS handshake with the daemon on port %u failed", (unsigned)port);
        SSL_free(ssl);
        close(*tcp_fd);
        *tcp_fd = -1;
        return NULL;
    }
    return ssl;
}

/* ---- the relay ---- */

typedef struct relay {
    SSL *ssl;
    int tcp;     /* to the daemon, carrying TLS */
    int plain;   /* the test's socket pair end */
} relay;

static bool write_all(int fd, const char *data, size_t n)
{
    while (n > 0) {
        ssize_t sent = send(fd, data, n, MSG_NOSIGNAL);
        if (sent < 0 && errno == EINTR)
            continue;
        if (sent <= 0)
            return false;
        data += sent;
        n -= (size_t)sent;
    }
    return true;
}

/* The daemon's side, decrypted, to the test; false once the daemon closed
 * (or the test did). */
static bool from_daemon(relay *r)
{
    char buf[16384];
    int got = SSL_read(r->ssl, buf, sizeof buf);
    if (got <= 0)
        return false;
    return write_all(r->plain, buf, (size_t)got);
}

/* The test's bytes, encrypted, to the daemon; *half_closed once the test shut
 * its sending side (a close_notify goes out, the daemon's replies still come). */
static bool from_test(relay *r, bool *half_closed)
{
    char buf[16384];
    ssize_t got = recv(r->plain, buf, sizeof buf, 0);
    if (got < 0 && errno == EINTR)
        return true;
    if (got <= 0) {
        SSL_shutdown(r->ssl);
        *half_closed = true;
        return true;
    }
    size_t written = 0;
    return SSL_write_ex(r->ssl, buf, (size_t)got, &written) == 1;
}

static void *run_relay(void *arg)
{
    relay *r = arg;
    bool half_closed = false, open = true;
    while (open) {
        struct pollfd fds[2] = {{.fd = r->tcp, .events = POLLIN}, {.fd = r->plain, .events = POLLIN}};
        bool pending = SSL_pending(r->ssl) > 0;
        if (!pending && poll(fds, half_closed ? 1 : 2, -1) < 0 && errno != EINTR)
            break;
        if (pending || (fds[0].revents & (POLLIN | POLLHUP | POLLERR)))
            open = from_daemon(r);
        if (open && !half_closed && (fds[1].revents & (POLLIN | POLLHUP | POLLERR)))
            open = from_test(r, &half_closed);
    }
    /* The test reads end of file where the daemon closed. */
    SSL_free(r->ssl);
    close(r->tcp);
    close(r->plain);
    free(r);
    return NULL;
}

int hx_tls_connect(hx_tls *t, uint16_t port)
{
    int tcp = -1;
    SSL *ssl = hx_tls_handshake(t, port, &tcp);
    return ssl ? hx_tls_relay(ssl, tcp) : -1;
}

int hx_tls_relay(SSL *ssl, int tcp)
{
    int pair[2];
    relay *r = malloc(sizeof *r);
    pthread_t thread;
    bool ok = r && socketpair(AF_UNIX, SOCK_STREAM, 0, pair) == 0;
    if (ok) {
        *r = (relay){.ssl = ssl, .tcp = tcp, .plain = pair[1]};
        ok = pthread_create(&thread, NULL, run_relay, r) == 0;
        if (ok)
            pthread_detach(thread);
        else
            close(pair[0]), close(pair[1]);
    }
    if (!ok) {
        CHECK_MSG(0, "cannot start a TLS relay");
        free(r);
        SSL_free(ssl);
        close(tcp);
        return -1;
    }
    return pair[0];
}
