/* fake_server.c — see fake_server.h. */
#include "fake_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fc_error.h"

const fc_limits fake_limits = { .max_particles = 1000, .max_width = 640, .max_height = 480, .max_message = 4096 };

struct fake_server {
    int listen_fd;
    uint16_t port;
    fake_script script;
    fake_connection conn;
    pthread_t thread;
};

static void *serve(void *arg)
{
    fake_server *s = arg;
    s->conn.fd = accept(s->listen_fd, NULL, NULL);
    if (s->conn.fd < 0) {
        s->conn.failures++;
        return NULL;
    }
    s->script(&s->conn);
    close(s->conn.fd);
    return NULL;
}

static int listen_loopback(uint16_t *port)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0)
        return -1;
    struct sockaddr_in addr = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
    socklen_t len = sizeof addr;
    if (bind(fd, (struct sockaddr *)&addr, sizeof addr) < 0 || listen(fd, 1) < 0 ||
        getsockname(fd, (struct sockaddr *)&addr, &len) < 0) {
        close(fd);
        return -1;
    }
    *port = ntohs(addr.sin_port);
    return fd;
}

fake_server *fake_server_start(fake_script script)
{
    fake_server *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->script = script;
    s->listen_fd = listen_loopback(&s->port);
    if (s->listen_fd < 0 || pthread_create(&s->thread, NULL, serve, s) != 0) {
        if (s->listen_fd >= 0)
            close(s->listen_fd);
        free(s);
        return NULL;
    }
    return s;
}

uint16_t fake_server_port(const fake_server *s)
{
    return s->port;
}

int fake_server_finish(fake_server *s)
{
    pthread_join(s->thread, NULL);
    close(s->listen_fd);
    int failures = s->conn.failures;
    free(s);
    return failures;
}

uint16_t fake_unused_port(void)
{
    uint16_t port = 0;
    int fd = listen_loopback(&port);
    if (fd >= 0)
        close(fd);
    return port;
}

bool fake_expect(fake_connection *conn, fc_msg_type type, fc_test_message *m)
{
    return fc_test_read_message(conn->fd, FAKE_IO_TIMEOUT_MS, m, NULL) == FC_OK && m->header.type == type;
}

/* Sends what the encoder put in `out` (when it succeeded) and frees it. */
static bool send_encoded(fake_connection *conn, fc_code encoded, fc_buf *out)
{
    bool ok = encoded == FC_OK && fc_test_send(conn->fd, out->data, out->len, NULL) == FC_OK;
    fc_buf_free(out);
    return ok;
}

bool fake_welcome(fake_connection *conn, uint32_t request_id)
{
    fc_welcome w;
    memset(&w, 0, sizeof w);
    w.version = FC_PROTOCOL_VERSION;
    w.limits = fake_limits;
    strcpy(w.server_version, FAKE_SERVER_VERSION);
    strcpy(w.renderer, FAKE_RENDERER);
    fc_buf out;
    fc_buf_init(&out);
    return send_encoded(conn, fc_wire_write_welcome(&out, request_id, &w, NULL), &out);
}

bool fake_error(fake_connection *conn, uint32_t request_id, fc_code code, const char *message)
{
    fc_error e;
    fc_error_set(&e, code, "%s", message);
    fc_buf out;
    fc_buf_init(&out);
    return send_encoded(conn, fc_wire_write_error(&out, request_id, &e, NULL), &out);
}

bool fake_image(fake_connection *conn, uint32_t request_id, const uint8_t *data, size_t size)
{
    fc_image_reply reply;
    memset(&reply, 0, sizeof reply);
    reply.width = 4;
    reply.height = 3;
    reply.format = FC_FORMAT_PNG;
    reply.aov = FC_AOV_COLOR;
    for (int i = 0; i < FC_STAGE_COUNT; i++)
        reply.stage_ms[i] = (float)i + 0.5f;
    reply.data = data;
    reply.size = size;
    fc_buf out;
    fc_buf_init(&out);
    return send_encoded(conn, fc_wire_write_image(&out, request_id, &reply, NULL), &out);
}
