/* test_socket.c — blocking socket helpers for protocol tests. */
#include "test_socket.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"

void fc_test_message_free(fc_test_message *m)
{
    free(m->payload);
    m->payload = NULL;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

fc_code fc_test_connect(uint16_t port, int *fd, fc_error *err)
{
    struct sockaddr_in addr = {0};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    *fd = socket(AF_INET, SOCK_STREAM, 0);
    if (*fd < 0)
        return fc_error_set(err, FC_ERR_IO, "socket: %s", strerror(errno));
    if (connect(*fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        int saved = errno;
        close(*fd);
        *fd = -1;
        return fc_error_set(err, FC_ERR_CONNECT, "connect 127.0.0.1:%u: %s", (unsigned)port, strerror(saved));
    }
    return FC_OK;
}

fc_code fc_test_send(int fd, const void *data, size_t size, fc_error *err)
{
    const uint8_t *p = data;
    while (size > 0) {
        ssize_t n = send(fd, p, size, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return fc_error_set(err, FC_ERR_IO, "send: %s", strerror(errno));
        p += n;
        size -= (size_t)n;
    }
    return FC_OK;
}

/* Exactly `size` bytes before the deadline. FC_ERR_CLOSED if EOF comes first
 * (*got says how many arrived). */
static fc_code receive_exact(int fd, void *buf, size_t size, double deadline, size_t *got, fc_error *err)
{
    uint8_t *p = buf;
    *got = 0;
    while (*got < size) {
        int left = (int)(deadline - now_ms());
        struct pollfd pfd = {fd, POLLIN, 0};
        int ready = left > 0 ? poll(&pfd, 1, left) : 0;
        if (ready < 0 && errno == EINTR)
            continue;
        if (ready <= 0)
            return fc_error_set(err, FC_ERR_IO, "timed out after %zu of %zu bytes", *got, size);
        ssize_t n = recv(fd, p + *got, size - *got, 0);
        if (n < 0 && errno == EINTR)
            continue;
        if (n == 0 || (n < 0 && errno == ECONNRESET))
            return fc_error_set(err, FC_ERR_CLOSED, "peer closed after %zu of %zu bytes", *got, size);
        if (n < 0)
            return fc_error_set(err, FC_ERR_IO, "recv: %s", strerror(errno));
        *got += (size_t)n;
    }
    return FC_OK;
}

fc_code fc_test_read_message(int fd, int timeout_ms, fc_test_message *m, fc_error *err)
{
    memset(m, 0, sizeof *m);
    double deadline = now_ms() + timeout_ms;
    uint8_t header[FC_WIRE_HEADER_SIZE];
    size_t got;
    fc_code code = receive_exact(fd, header, sizeof header, deadline, &got, err);
    if (code != FC_OK)
        return code;
    fc_error header_err;
    if (fc_wire_decode_header(header, UINT32_MAX, &m->header, &header_err) != FC_OK)
        return fc_error_set(err, FC_ERR_PROTOCOL, "bad header: %s", header_err.message);
    m->payload = malloc(m->header.length ? m->header.length : 1);
    if (!m->payload)
        return fc_error_set(err, FC_ERR_NOMEM, "payload of %u bytes", (unsigned)m->header.length);
    code = receive_exact(fd, m->payload, m->header.length, deadline, &got, err);
    if (code != FC_OK)
        fc_test_message_free(m);
    return code;
}

fc_code fc_test_expect_closed(int fd, int timeout_ms, fc_error *err)
{
    uint8_t byte;
    size_t got;
    fc_code code = receive_exact(fd, &byte, 1, now_ms() + timeout_ms, &got, err);
    if (code == FC_ERR_CLOSED)
        return FC_OK;
    if (code == FC_OK)
        return fc_error_set(err, FC_ERR_PROTOCOL, "expected the connection to close, but more bytes arrived");
    return code;
}

fc_code fc_test_handshake(int fd, uint32_t request_id, fc_welcome *welcome, fc_error *err)
{
    fc_hello hello = {FC_PROTOCOL_VERSION, FC_PROTOCOL_VERSION, 0, "fluidcast-test", ""};
    fc_buf out;
    fc_buf_init(&out);
    fc_code code = fc_wire_write_hello(&out, request_id, &hello, err);
    if (code == FC_OK)
        code = fc_test_send(fd, out.data, out.len, err);
    fc_buf_free(&out);
    fc_test_message reply;
    if (code == FC_OK)
        code = fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &reply, err);
    if (code != FC_OK)
        return code;
    if (reply.header.type != FC_MSG_WELCOME || reply.header.request_id != request_id)
        code = fc_error_set(err, FC_ERR_PROTOCOL, "HELLO answered by type %u, request %u",
                            (unsigned)reply.header.type, (unsigned)reply.header.request_id);
    else
        code = fc_wire_read_welcome(reply.payload, reply.header.length, welcome, err);
    fc_test_message_free(&reply);
    return code;
}

fc_code fc_test_read_error(int fd, uint32_t *request_id, fc_error *remote, fc_error *err)
{
    fc_test_message m;
    fc_code code = fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &m, err);
    if (code != FC_OK)
        return code;
    *request_id = m.header.request_id;
    if (m.header.type != FC_MSG_ERROR)
        code = fc_error_set(err, FC_ERR_PROTOCOL, "expected ERROR, got message type %u", (unsigned)m.header.type);
    else
        code = fc_wire_read_error(m.payload, m.header.length, remote, err);
    fc_test_message_free(&m);
    return code;
}
