/* test_socket.h — blocking socket helpers for protocol tests: connect, send
 * raw bytes, read one whole message with a timeout, observe a close. */
#ifndef FC_TEST_SOCKET_H
#define FC_TEST_SOCKET_H

#include <stddef.h>
#include <stdint.h>

#include "wire.h"

#define FC_TEST_IO_TIMEOUT_MS 30000

/* A message as received: header and its payload (malloc'd). */
typedef struct fc_test_message {
    fc_msg_header header;
    uint8_t *payload;
} fc_test_message;

void fc_test_message_free(fc_test_message *m);

/* Connects to 127.0.0.1:port. */
fc_code fc_test_connect(uint16_t port, int *fd, fc_error *err);

/* Sends all `size` bytes (raw: they need not form valid messages). */
fc_code fc_test_send(int fd, const void *data, size_t size, fc_error *err);

/* Reads one whole message within timeout_ms. FC_ERR_CLOSED when the peer
 * closed first, FC_ERR_IO on timeout or socket error, FC_ERR_PROTOCOL when
 * the bytes do not start with a valid header. */
fc_code fc_test_read_message(int fd, int timeout_ms, fc_test_message *m, fc_error *err);

/* FC_OK when the peer closes (EOF or reset) within timeout_ms without sending
 * anything more; FC_ERR_PROTOCOL if bytes arrive, FC_ERR_IO on timeout. */
fc_code fc_test_expect_closed(int fd, int timeout_ms, fc_error *err);

/* Sends HELLO (version 1..1) with request_id and reads the reply into *welcome.
 * FC_ERR_PROTOCOL when the reply is not a WELCOME echoing request_id. */
fc_code fc_test_handshake(int fd, uint32_t request_id, fc_welcome *welcome, fc_error *err);

/* Reads one message and requires an ERROR: its request_id and the error it carries. */
fc_code fc_test_read_error(int fd, uint32_t *request_id, fc_error *remote, fc_error *err);

#endif
