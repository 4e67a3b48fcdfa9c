/* test_hardening_tls.c — hostility aimed at the TLS layer itself, against a
 * daemon with a certificate (the protocol's own cases run over TLS in the
 * hardening_*_tls tests): a handshake record of garbage, a record cut short,
 * a record longer than TLS allows; each connection is closed (at most a TLS
 * alert comes back) and the witness, a TLS client connected the whole time,
 * is still served. A key update in the middle of a connection is legitimate
 * TLS 1.3: the connection goes on rendering. */
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "hardening_harness.h"
#include "hardening_tls.h"
#include "test_socket.h"
#include "test_util.h"

#define TLS_RECORD_HANDSHAKE 0x16
#define TLS_RECORD_ALERT 0x15
#define TLS_RECORD_APPLICATION_DATA 0x17

/* An alert in TLS 1.3 after the handshake is encrypted: one application-data
 * record of 5 header bytes, the alert's 2, its content type's 1 and a 16-byte tag. */
#define ENCRYPTED_ALERT_BYTES 24u

/* Reads fd until the daemon closes it (at most 10 s); true when it did, and
 * what came before the end was nothing or one TLS alert (in clear during the
 * handshake, encrypted after it). */
static bool closed_with_at_most_an_alert(int fd, bool encrypted, const char *what)
{
    unsigned char buf[4096], first = 0;
    size_t total = 0;
    for (;;) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        if (poll(&p, 1, 10000) <= 0) {
            CHECK_MSG(0, "%s: the daemon did not close the connection within 10 s", what);
            return false;
        }
        ssize_t got = recv(fd, buf, sizeof buf, 0);
        if (got <= 0)
            break;
        if (total == 0)
            first = buf[0];
        total += (size_t)got;
    }
    bool alert = total == 0 || first == TLS_RECORD_ALERT ||
                 (encrypted && first == TLS_RECORD_APPLICATION_DATA && total == ENCRYPTED_ALERT_BYTES);
    CHECK_MSG(alert, "%s: the daemon answered %zu byte(s) that are not a TLS alert", what, total);
    printf("%s: closed after %zu byte(s) of alert\n", what, total);
    return alert;
}

/* A record header of `type` announcing `length` bytes, then `sent` bytes of it. */
static void send_record(int fd, unsigned char type, unsigned length, size_t sent)
{
    unsigned char head[5] = {type, 0x03, 0x03, (unsigned char)(length >> 8), (unsigned char)length};
    hx_send(fd, head, sizeof head);
    unsigned char *body = malloc(sent ? sent : 1);
    CHECK(body != NULL);
    if (!body)
        return;
    memset(body, 0xA5, sent);
    hx_send(fd, body, sent);
    free(body);
}

static void garbage_handshake(hx_env *env)
{
    int fd = -1;
    fc_error err;
    CHECK_MSG(fc_test_connect(env->daemon.port, &fd, &err) == FC_OK, "%s", err.message);
    if (fd < 0)
        return;
    send_record(fd, TLS_RECORD_HANDSHAKE, 64, 64);   /* not a ClientHello */
    closed_with_at_most_an_alert(fd, false, "garbage in a handshake record");
    close(fd);
    hx_expect_witness_served(env);
}

/* After a real handshake, a raw record the client's TLS would never write. */
static void hostile_record(hx_env *env, unsigned length, size_t sent, const char *what)
{
    int tcp = -1;
    SSL *ssl = hx_tls_handshake(env->tls, env->daemon.port, &tcp);
    if (!ssl)
        return;
    send_record(tcp, TLS_RECORD_APPLICATION_DATA, length, sent);
    shutdown(tcp, SHUT_WR);
    closed_with_at_most_an_alert(tcp, true, what);
    SSL_free(ssl);
    close(tcp);
    hx_expect_witness_served(env);
}

static void key_update(hx_env *env)
{
    int tcp = -1;
    SSL *ssl = hx_tls_handshake(env->tls, env->daemon.port, &tcp);
    if (!ssl)
        return;
    CHECK_MSG(SSL_key_update(ssl, SSL_KEY_UPDATE_REQUESTED) == 1, "the client cannot ask for a key update");
    int fd = hx_tls_relay(ssl, tcp);   /* the update goes out with the first bytes */
    if (fd < 0)
        return;
    fc_buf out;
    fc_buf_init(&out);
    hx_hello(&out, 1, FC_PROTOCOL_VERSION, FC_PROTOCOL_VERSION, 0);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_reply_type(fd, 1, FC_MSG_WELCOME);
    hx_expect_renders(fd, 10);
    printf("key update: the connection went on rendering\n");
    close(fd);
    hx_expect_witness_served(env);
}

int main(void)
{
    setenv("FC_HARDENING_TRANSPORT", "tls", 1);
    hx_env env;
    if (!hx_env_start(&env, NULL))
        return hx_exit_status(1);
    garbage_handshake(&env);
    hostile_record(&env, 1000, 10, "a record cut short");
    hostile_record(&env, 16384 + 2048 + 1, 64, "a record longer than TLS allows");
    key_update(&env);
    hx_env_stop(&env);
    return hx_exit_status(test_result());
}
