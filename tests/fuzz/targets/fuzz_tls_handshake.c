/* fuzz_tls_handshake.c — libFuzzer target for the daemon's TLS transport
 * (server/daemon/net/transport.c, tls_server.c) on the bytes a client sends
 * first: a ClientHello and whatever follows it, garbage, or a client that
 * speaks the protocol in clear. The input is written into one end of a socket
 * pair and the daemon's side runs its non-blocking handshake step by step, as
 * its event loop would, then reads what the session decrypts.
 *
 * Contract: a first byte that does not open a TLS handshake record (0x16) is a
 * plaintext peer, and only such a byte is; a failed handshake says why; no
 * step count is unbounded; nothing crashes, leaks or reads out of bounds. The
 * certificate is a test-only self-signed pair made for this target. */
#include <fcntl.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fuzz_check.h"
#include "net/transport.h"

#define TLS_HANDSHAKE_RECORD 0x16
#define MAX_INPUT (64u * 1024u)   /* one socket buffer's worth: the pair never blocks the writer */
#define MAX_STEPS 64

static const char CERT[] =
    "-----BEGIN CERTIFICATE-----\n"
    "MIIBkTCCATagAwIBAgIUZr4IRKfjjx759GYBj05lEopivYowCgYIKoZIzj0EAwIw\n"
    "FDESMBAGA1UEAwwJbG9jYWxob3N0MCAXDTI2MTIwNTA0NTAxMVoYDzIxMjYxMTEx\n"
    "MDQ1MDExWjAUMRIwEAYDVQQDDAlsb2NhbGhvc3QwWTATBgcqhkjOPQIBBggqhkjO\n"
    "PQMBBwNCAATO+uSGXgfC/G9adKtbXj76Yj9FsmOEhIKb8RSt3NFlKvFpo8OI3EUd\n"
    "v1UOawFSobg/e33XU2Oi5qsATmX36/4no2QwYjAdBgNVHQ4EFgQUf1SK2tycRTx9\n"
    "tdBgZmx6L4uDUZQwHwYDVR0jBBgwFoAUf1SK2tycRTx9tdBgZmx6L4uDUZQwDwYD\n"
    "VR0TAQH/BAUwAwEB/zAPBgNVHREECDAGhwR/AAABMAoGCCqGSM49BAMCA0kAMEYC\n"
    "IQCzXrFNUgfhxlthMbncrSD599yDGNuX7NUk1NcJ/j7j+QIhAJCXtI+sZnpV8z/j\n"
    "EZcTkRAj07dp+V3mXUYk89X1Q6Dz\n"
    "-----END CERTIFICATE-----\n";
static const char KEY[] =
    "-----BEGIN PRIVATE KEY-----\n"
    "MIGHAgEAMBMGByqGSM49AgEGCCqGSM49AwEHBG0wawIBAQQgeetcej3UmvjxnSMs\n"
    "TN93iXPefZGxxwsBOCswF4lenhqhRANCAATO+uSGXgfC/G9adKtbXj76Yj9FsmOE\n"
    "hIKb8RSt3NFlKvFpo8OI3EUdv1UOawFSobg/e33XU2Oi5qsATmX36/4n\n"
    "-----END PRIVATE KEY-----\n";

static fc_tls_server *server;

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    FUZZ_REQUIRE(f && fputs(text, f) >= 0 && fclose(f) == 0, "cannot write %s", path);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    static char dir[] = "/tmp/fc_fuzz_tls_XXXXXX", cert[64], key[64];
    FUZZ_REQUIRE(mkdtemp(dir) != NULL, "mkdtemp failed");
    snprintf(cert, sizeof cert, "%s/cert.pem", dir);
    snprintf(key, sizeof key, "%s/key.pem", dir);
    write_file(cert, CERT);
    write_file(key, KEY);
    fc_tls_server_files files = {cert, key, NULL};
    fc_error err;
    FUZZ_REQUIRE(fc_tls_server_create(&files, &server, &err) == FC_OK, "%s", err.message);
    unlink(cert);
    unlink(key);
    rmdir(dir);
    return 0;
}

/* What the daemon wrote back (its ServerHello, an alert) is read and dropped,
 * so that its writes never wait on us. */
static void drain(int fd)
{
    char buf[4096];
    while (recv(fd, buf, sizeof buf, MSG_DONTWAIT) > 0)
        ;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > MAX_INPUT)
        size = MAX_INPUT;
    int pair[2];
    FUZZ_REQUIRE(socketpair(AF_UNIX, SOCK_STREAM, 0, pair) == 0, "socketpair failed");
    FUZZ_REQUIRE(fcntl(pair[1], F_SETFL, O_NONBLOCK) == 0, "fcntl failed");
    if (size > 0)
        FUZZ_REQUIRE(send(pair[0], data, size, MSG_NOSIGNAL) == (ssize_t)size, "the input did not fit the pair");
    shutdown(pair[0], SHUT_WR);

    fc_transport t;
    fc_error err;
    FUZZ_REQUIRE(fc_transport_tls(&t, pair[1], server, &err) == FC_OK, "%s", err.message);
    fc_handshake_result result = FC_HANDSHAKE_WAITING;
    for (int step = 0; step < MAX_STEPS && result == FC_HANDSHAKE_WAITING; step++) {
        fc_error why = {FC_OK, ""};
        result = fc_transport_handshake(&t, &why);
        drain(pair[0]);
        if (result == FC_HANDSHAKE_FAILED)
            FUZZ_REQUIRE(why.message[0] != '\0', "a failed handshake without a reason");
    }
    FUZZ_REQUIRE(result != FC_HANDSHAKE_WAITING, "still waiting after %d steps with the input at its end", MAX_STEPS);
    if (size > 0)
        FUZZ_REQUIRE((result == FC_HANDSHAKE_PLAINTEXT_PEER) == (data[0] != TLS_HANDSHAKE_RECORD),
                     "first byte 0x%02x, yet the handshake result %d", data[0], (int)result);
    if (result == FC_HANDSHAKE_DONE || result == FC_HANDSHAKE_PLAINTEXT_PEER) {
        char buf[4096];
        for (int reads = 0; reads < MAX_STEPS && fc_transport_recv(&t, buf, sizeof buf) > 0; reads++)
            ;
    }
    fc_transport_close(&t);
    close(pair[0]);
    return 0;
}
