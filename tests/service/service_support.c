/* service_support.c — see service_support.h. */
#include "service_support.h"

#include <arpa/inet.h>
#include <errno.h>
#include <math.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"

void svc_start_daemon(fc_test_daemon *d, const char *const *extra_args)
{
    fc_error err;
    if (fc_test_daemon_start(d, extra_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start the daemon: %s\n", err.message);
        exit(1);
    }
}

bool svc_stop_daemon(fc_test_daemon *d)
{
    fc_error err;
    if (fc_test_daemon_stop(d, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK)
        return true;
    fprintf(stderr, "stopping the daemon: %s\n", err.message);
    return false;
}

const char *svc_address(const fc_test_daemon *d)
{
    /* One daemon per test process: a static buffer is enough and keeps call sites short. */
    static char address[32];
    snprintf(address, sizeof address, "127.0.0.1:%u", (unsigned)d->port);
    return address;
}

/* Before connect(), so the window the kernel announces is small from the start. */
static int connect_socket(uint16_t port, int receive_buffer)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0)
        return -1;
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_port = htons(port)};
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if ((receive_buffer > 0 &&
         setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer) != 0) ||
        connect(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        fprintf(stderr, "connect 127.0.0.1:%u: %s\n", (unsigned)port, strerror(errno));
        close(fd);
        return -1;
    }
    return fd;
}

int svc_raw_connect(uint16_t port, uint32_t capabilities, int receive_buffer, fc_welcome *welcome)
{
    fc_error err;
    int fd = connect_socket(port, receive_buffer);
    if (fd < 0)
        return -1;
    fc_hello hello = {FC_PROTOCOL_VERSION, FC_PROTOCOL_VERSION, capabilities, "service-test", ""};
    fc_buf out;
    fc_buf_init(&out);
    fc_test_message reply = {0};
    fc_code code = fc_wire_write_hello(&out, 1, &hello, &err);
    if (code == FC_OK)
        code = fc_test_send(fd, out.data, out.len, &err);
    if (code == FC_OK)
        code = fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &reply, &err);
    if (code == FC_OK && reply.header.type != FC_MSG_WELCOME)
        code = fc_error_set(&err, FC_ERR_PROTOCOL, "HELLO answered by type %u", (unsigned)reply.header.type);
    if (code == FC_OK)
        code = fc_wire_read_welcome(reply.payload, reply.header.length, welcome, &err);
    fc_test_message_free(&reply);
    fc_buf_free(&out);
    if (code != FC_OK) {
        fprintf(stderr, "handshake: %s\n", err.message);
        close(fd);
        return -1;
    }
    return fd;
}

bool svc_send(int fd, fc_buf *b)
{
    fc_error err;
    bool ok = !b->failed && fc_test_send(fd, b->data, b->len, &err) == FC_OK;
    if (!ok)
        fprintf(stderr, "send failed\n");
    fc_buf_reset(b);
    return ok;
}

bool svc_expect_error(int fd, uint32_t request_id, fc_code code, fc_error *remote)
{
    uint32_t got_id = 0;
    fc_error err;
    fc_error_clear(remote);
    if (fc_test_read_error(fd, &got_id, remote, &err) != FC_OK) {
        fprintf(stderr, "expected ERROR %d for request %u: %s\n", (int)code, request_id, err.message);
        return false;
    }
    if (got_id == request_id && remote->code == code)
        return true;
    fprintf(stderr, "got ERROR %d (%s) for request %u, expected ERROR %d for request %u\n", (int)remote->code,
            remote->message, got_id, (int)code, request_id);
    return false;
}

fc_code svc_grid_frame(float dz, fc_frame *frame, fc_error *err)
{
    const int side = SVC_GRID_SIDE;
    fc_code code = fc_frame_alloc(frame, (uint64_t)side * side * side, 0, err);
    if (code != FC_OK)
        return code;
    float *p = frame->positions;
    for (int z = 0; z < side; z++)
        for (int y = 0; y < side; y++)
            for (int x = 0; x < side; x++) {
                *p++ = (float)(x - side / 2) * SVC_GRID_SPACING;
                *p++ = (float)(y - side / 2) * SVC_GRID_SPACING;
                *p++ = (float)(z - side / 2) * SVC_GRID_SPACING + dz;
            }
    return FC_OK;
}

void svc_axis_camera(float eye_z, uint32_t width, uint32_t height, fc_camera *cam)
{
    *cam = (fc_camera){.eye = {0.0f, 0.0f, eye_z}, .target = {0.0f, 0.0f, 0.0f}, .up = {0.0f, 1.0f, 0.0f},
                       .fov_y_deg = 40.0f, .width = width, .height = height};
}

double svc_axis_depth(float eye_z, float dz)
{
    return (double)eye_z - (SVC_GRID_FRONT + dz) - SVC_RADIUS;
}

void svc_settings(fc_settings *s)
{
    fc_settings_default(s);
    s->radius = SVC_RADIUS;
    s->smoothing = FC_SMOOTHING_NONE;
}

fc_client *svc_client(const fc_test_daemon *d, const char *name)
{
    fc_connect_options options = {.client_name = name, .reply_timeout_ms = FC_TEST_IO_TIMEOUT_MS};
    fc_client *c = NULL;
    fc_error err;
    if (fc_client_connect(svc_address(d), &options, &c, &err) != FC_OK)
        fprintf(stderr, "connect: %s\n", err.message);
    return c;
}

float svc_raw_centre(const fc_image_result *image)
{
    if (!image->data || image->size != (size_t)image->width * image->height * sizeof(float))
        return -1.0f;
    float value;
    size_t at = ((size_t)(image->height / 2) * image->width + image->width / 2) * sizeof(float);
    memcpy(&value, image->data + at, sizeof value);
    return value;
}

double svc_now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

void svc_sleep_ms(int ms)
{
    struct timespec pause = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&pause, NULL);
}
