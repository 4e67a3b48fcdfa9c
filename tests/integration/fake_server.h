/* fake_server.h — a scripted stand-in for fluidcastd on a loopback port, so
 * libfluidcast's handling of replies the real daemon rarely or never sends
 * (garbage, early close, errors for earlier requests) can be tested exactly.
 * The script runs on its own thread and serves one connection; it reads with
 * the test_socket.h helpers and answers with the fake_* replies below. */
#ifndef FC_FAKE_SERVER_H
#define FC_FAKE_SERVER_H

#include <stdbool.h>
#include <stdint.h>

#include "support/test_socket.h"

typedef struct fake_server fake_server;

/* What a script sees: the accepted connection and a count of what it found wrong. */
typedef struct fake_connection {
    int fd;
    int failures;
} fake_connection;

typedef void (*fake_script)(fake_connection *conn);

/* Listens on 127.0.0.1 (any free port) and runs `script` on the first
 * connection in a thread. NULL when the socket or thread cannot be set up. */
fake_server *fake_server_start(fake_script script);
uint16_t fake_server_port(const fake_server *s);
/* Waits for the script to end, frees the server, returns the script's failures. */
int fake_server_finish(fake_server *s);

/* A loopback port nobody listens on (bound, then released). */
uint16_t fake_unused_port(void);

/* Reads the next message into *m (free with fc_test_message_free); true when it
 * arrived and has type `type`. */
bool fake_expect(fake_connection *conn, fc_msg_type type, fc_test_message *m);

/* The fake's WELCOME: fake_limits, FAKE_SERVER_VERSION, FAKE_RENDERER. */
bool fake_welcome(fake_connection *conn, uint32_t request_id);
bool fake_error(fake_connection *conn, uint32_t request_id, fc_code code, const char *message);
/* A 4x3 PNG-labelled IMAGE carrying `data`; stage i took i + 0.5 ms. */
bool fake_image(fake_connection *conn, uint32_t request_id, const uint8_t *data, size_t size);

extern const fc_limits fake_limits;
#define FAKE_SERVER_VERSION "fake 9.9"
#define FAKE_RENDERER "fake GL renderer"
#define FAKE_IO_TIMEOUT_MS 10000

#endif
