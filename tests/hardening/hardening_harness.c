/* hardening_harness.c — see hardening_harness.h. */
#include "hardening_harness.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"
#include "hardening_tls.h"
#include "integration/scene_fixtures.h"
#include "test_scene.h"
#include "test_util.h"
#include "wire_scene.h"
#include "wire_session.h"

#define WITNESS_FIRST_ID 10000u
#define MAX_DAEMON_ARGS 16

/* The cube's front particles sit at z = 0.25, 3 units from the eye, 0.1 apart
 * at +-0.05, +-0.15, ...; the estimated radius is 0.9 x 0.1. The centre pixel
 * of the 32 x 32 image looks half a pixel off the axis: at the front that is
 * 2.66 x tan(20 deg) / 32 = 0.030 in x and y, so its ray meets the sphere
 * around (0.05, -0.05, 0.25) at depth 2.75 - sqrt(0.09^2 - 2 x 0.02^2) = 2.6646. */
#define CUBE_CENTRE_DEPTH 2.6646
#define CUBE_DEPTH_TOLERANCE 0.01

/* ---- raw messages ---- */

void hx_bytes(fc_buf *out, const void *p, size_t n)
{
    if (n == 0 || !fc_buf_reserve(out, n))
        return;
    memcpy(out->data + out->len, p, n);
    out->len += n;
}

static void put_le(fc_buf *out, uint64_t v, int size)
{
    uint8_t bytes[8];
    for (int i = 0; i < size; i++)
        bytes[i] = (uint8_t)(v >> (8 * i));
    hx_bytes(out, bytes, (size_t)size);
}

void hx_u16(fc_buf *out, uint16_t v) { put_le(out, v, 2); }
void hx_u32(fc_buf *out, uint32_t v) { put_le(out, v, 4); }
void hx_u64(fc_buf *out, uint64_t v) { put_le(out, v, 8); }

void hx_f32(fc_buf *out, float v)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    hx_u32(out, bits);
}

void hx_str(fc_buf *out, const char *s)
{
    size_t n = strlen(s);
    hx_u16(out, (uint16_t)n);
    hx_bytes(out, s, n);
}

void hx_header(fc_buf *out, uint16_t type, uint16_t flags, uint32_t request_id, uint32_t length)
{
    hx_bytes(out, "FCST", 4);
    hx_u16(out, type);
    hx_u16(out, flags);
    hx_u32(out, request_id);
    hx_u32(out, length);
}

size_t hx_begin(fc_buf *out, uint16_t type, uint32_t request_id)
{
    size_t start = out->len;
    hx_header(out, type, 0, request_id, 0);
    return start;
}

void hx_end(fc_buf *out, size_t start)
{
    if (out->failed)
        return;
    size_t length = out->len - start - FC_WIRE_HEADER_SIZE;
    for (int i = 0; i < 4; i++)
        out->data[start + 12 + (size_t)i] = (uint8_t)(length >> (8 * i));
}

void hx_hello(fc_buf *out, uint32_t request_id, uint32_t vmin, uint32_t vmax, uint32_t capabilities)
{
    size_t at = hx_begin(out, FC_MSG_HELLO, request_id);
    hx_u32(out, vmin);
    hx_u32(out, vmax);
    hx_u32(out, capabilities);
    hx_str(out, "fluidcast-hardening");
    hx_end(out, at);
}

/* ---- time ---- */

double hx_now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

void hx_sleep_ms(int ms)
{
    struct timespec pause = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&pause, NULL);
}

/* ---- connections ---- */

int hx_connect(const hx_env *env)
{
    if (env->tls)
        return hx_tls_connect(env->tls, env->daemon.port);
    int fd = -1;
    fc_error err;
    CHECK_MSG(fc_test_connect(env->daemon.port, &fd, &err) == FC_OK, "%s", err.message);
    return fd;
}

void hx_send(int fd, const void *data, size_t size)
{
    fc_error err;
    CHECK_MSG(fc_test_send(fd, data, size, &err) == FC_OK, "%s", err.message);
}

void hx_send_buf(int fd, fc_buf *out)
{
    CHECK_MSG(!out->failed, "out of memory building a message");
    hx_send(fd, out->data, out->len);
    fc_buf_reset(out);
}

/* Reads the reply to request_id and requires it to be a message of `type`; on
 * success *m holds it (free it with fc_test_message_free). */
static bool read_reply(int fd, uint32_t request_id, uint16_t type, fc_test_message *m)
{
    fc_error err;
    if (fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, m, &err) != FC_OK) {
        CHECK_MSG(0, "expected message type %u for request %u: %s", type, request_id, err.message);
        return false;
    }
    if (m->header.type == type && m->header.request_id == request_id)
        return true;
    if (m->header.type == FC_MSG_ERROR) {
        fc_error remote = {0};
        fc_wire_read_error(m->payload, m->header.length, &remote, &err);
        CHECK_MSG(0, "request %u answered by ERROR %d (%s), expected type %u for request %u", m->header.request_id,
                  remote.code, remote.message, type, request_id);
    } else {
        CHECK_MSG(0, "got type %u for request %u, expected type %u for request %u", m->header.type,
                  m->header.request_id, type, request_id);
    }
    fc_test_message_free(m);
    return false;
}

void hx_expect_reply_type(int fd, uint32_t request_id, uint16_t type)
{
    fc_test_message m;
    if (read_reply(fd, request_id, type, &m))
        fc_test_message_free(&m);
}

int hx_connect_greeted(const hx_env *env, uint32_t capabilities)
{
    int fd = hx_connect(env);
    if (fd < 0)
        return fd;
    fc_buf out;
    fc_buf_init(&out);
    hx_hello(&out, 1, FC_PROTOCOL_VERSION, FC_PROTOCOL_VERSION, capabilities);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_reply_type(fd, 1, FC_MSG_WELCOME);
    return fd;
}

void hx_publish(int fd, const char *session)
{
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_wire_write_publish(&out, 2, session, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_reply_type(fd, 2, FC_MSG_SESSION_STATE);
}

/* ---- expectations ---- */

void hx_expect_error_mentioning(int fd, uint32_t request_id, fc_code code, const char *phrase)
{
    uint32_t got_id = 0;
    fc_error remote = {0}, err;
    if (fc_test_read_error(fd, &got_id, &remote, &err) != FC_OK) {
        CHECK_MSG(0, "expected ERROR %d (%s) for request %u: %s", code, fc_code_name(code), request_id,
                  err.message);
        return;
    }
    CHECK_MSG(got_id == request_id, "ERROR %d answers request %u, expected %u", remote.code, got_id, request_id);
    CHECK_MSG(remote.code == code, "ERROR code %d (%s: %s), expected %d (%s)", remote.code,
              fc_code_name(remote.code), remote.message, code, fc_code_name(code));
    CHECK_MSG(remote.message[0] != '\0', "ERROR %d without a reason", code);
    CHECK_MSG(!phrase || strstr(remote.message, phrase), "ERROR %d says \"%s\", expected it to mention \"%s\"", code,
              remote.message, phrase);
}

void hx_expect_error(int fd, uint32_t request_id, fc_code code)
{
    hx_expect_error_mentioning(fd, request_id, code, NULL);
}

void hx_expect_closed(int fd)
{
    fc_error err;
    CHECK_MSG(fc_test_expect_closed(fd, FC_TEST_IO_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
}

static float depth_at(const fc_image_reply *image, uint32_t x, uint32_t y)
{
    float value;
    memcpy(&value, image->data + 4 * ((size_t)y * image->width + x), sizeof value);
    return value;
}

/* The cube seen from the front: fluid at the centre, nothing in the corners. */
static void check_cube_depth(const fc_image_reply *image)
{
    const uint32_t side = HX_IMAGE_SIDE;
    CHECK_MSG(image->width == side && image->height == side, "image %ux%u", image->width, image->height);
    CHECK(image->format == FC_FORMAT_RAW && image->aov == FC_AOV_DEPTH);
    CHECK_MSG(image->size == (uint64_t)side * side * sizeof(float), "RAW depth of %llu bytes",
              (unsigned long long)image->size);
    if (image->width != side || image->height != side || image->size != (uint64_t)side * side * sizeof(float))
        return;
    float centre = depth_at(image, side / 2, side / 2);
    CHECK_NEAR(centre, CUBE_CENTRE_DEPTH, CUBE_DEPTH_TOLERANCE);
    float corners[4] = {depth_at(image, 0, 0), depth_at(image, side - 1, 0), depth_at(image, 0, side - 1),
                        depth_at(image, side - 1, side - 1)};
    for (int i = 0; i < 4; i++)
        CHECK_MSG(corners[i] == 0.0f, "corner %d depth %g, expected 0 (no fluid)", i, corners[i]);
}

static void check_cube_reply(const fc_test_message *reply, uint32_t render_id)
{
    fc_image_reply image;
    fc_error err;
    if (fc_wire_read_image(reply->payload, reply->header.length, &image, &err) == FC_OK)
        check_cube_depth(&image);
    else
        CHECK_MSG(0, "RENDER %u: unreadable IMAGE: %s", render_id, err.message);
}

void hx_expect_cube_image(int fd, uint32_t render_id)
{
    fc_test_message reply;
    if (!read_reply(fd, render_id, FC_MSG_IMAGE, &reply))
        return;
    check_cube_reply(&reply, render_id);
    fc_test_message_free(&reply);
}

bool hx_expect_cube_image_or_error(int fd, uint32_t render_id, fc_code code, const char *phrase)
{
    fc_test_message reply;
    fc_error err;
    if (fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &reply, &err) != FC_OK) {
        CHECK_MSG(0, "no reply to RENDER %u: %s", render_id, err.message);
        return false;
    }
    bool failed = reply.header.type == FC_MSG_ERROR;
    fc_error remote = {0};
    CHECK_MSG(reply.header.request_id == render_id, "reply to request %u, expected %u", reply.header.request_id,
              render_id);
    if (failed) {
        CHECK_CODE(fc_wire_read_error(reply.payload, reply.header.length, &remote, &err), FC_OK);
        CHECK_MSG(remote.code == code && strstr(remote.message, phrase), "RENDER %u: ERROR %d (%s), expected %d (%s)",
                  render_id, remote.code, remote.message, code, phrase);
    } else {
        CHECK_MSG(reply.header.type == FC_MSG_IMAGE, "RENDER %u answered by type %u", render_id, reply.header.type);
        check_cube_reply(&reply, render_id);
    }
    fc_test_message_free(&reply);
    return failed;
}

void hx_send_magenta_background(int fd, uint32_t request_id)
{
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_encoded_image file = {png_magenta_4x4, png_magenta_4x4_size};
    CHECK_CODE(fc_wire_write_background(&out, request_id, &file, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
}

void hx_send_render(int fd, uint32_t request_id, fc_image_format format, fc_aov aov)
{
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_render_request request = {format, 0, aov};
    CHECK_CODE(fc_wire_write_render(&out, request_id, &request, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
}

static bool is_magenta(const uint8_t *rgba)
{
    static const int magenta[3] = {200, 40, 120};   /* png_magenta_4x4 */
    for (int c = 0; c < 3; c++)
        if (abs(rgba[c] - magenta[c]) > 2)
            return false;
    return true;
}

static void check_magenta_image(const fc_image_reply *image, uint32_t render_id)
{
    const uint32_t side = HX_IMAGE_SIDE;
    if (image->width != side || image->height != side || image->format != FC_FORMAT_RAW ||
        image->aov != FC_AOV_COLOR || image->size != (uint64_t)side * side * 4) {
        CHECK_MSG(0, "RENDER %u: expected %ux%u RAW colour, got %ux%u format %d aov %d", render_id, side, side,
                  image->width, image->height, (int)image->format, (int)image->aov);
        return;
    }
    const uint32_t corners[4][2] = {{0, 0}, {side - 1, 0}, {0, side - 1}, {side - 1, side - 1}};
    for (int i = 0; i < 4; i++) {
        const uint8_t *p = image->data + 4 * ((size_t)corners[i][1] * side + corners[i][0]);
        CHECK_MSG(is_magenta(p), "RENDER %u: corner %d is (%u,%u,%u), not the background", render_id, i, p[0], p[1],
                  p[2]);
    }
    const uint8_t *centre = image->data + 4 * ((size_t)(side / 2) * side + side / 2);
    CHECK_MSG(!is_magenta(centre), "RENDER %u: no fluid at the centre", render_id);
}

void hx_expect_magenta_image(int fd, uint32_t render_id, fc_buf *pixels)
{
    fc_test_message reply;
    if (!read_reply(fd, render_id, FC_MSG_IMAGE, &reply))
        return;
    fc_image_reply image;
    fc_error err;
    if (fc_wire_read_image(reply.payload, reply.header.length, &image, &err) == FC_OK) {
        check_magenta_image(&image, render_id);
        if (pixels)
            hx_bytes(pixels, image.data, (size_t)image.size);
    } else {
        CHECK_MSG(0, "RENDER %u: unreadable IMAGE: %s", render_id, err.message);
    }
    fc_test_message_free(&reply);
}

void hx_write_render_sequence(fc_buf *out, uint32_t first_id)
{
    fc_render_request request = {FC_FORMAT_RAW, 0, FC_AOV_DEPTH};
    fc_error err;
    CHECK_MSG(fc_test_write_render_sequence(out, first_id, HX_IMAGE_SIDE, HX_IMAGE_SIDE, &request, &err) == FC_OK,
              "%s", err.message);
}

void hx_expect_renders(int fd, uint32_t first_id)
{
    fc_buf out;
    fc_buf_init(&out);
    hx_write_render_sequence(&out, first_id);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_cube_image(fd, first_id + 2);
}

void hx_expect_witness_served(hx_env *env)
{
    if (env->witness_fd < 0)
        return;
    hx_expect_renders(env->witness_fd, env->witness_next_id);
    env->witness_next_id += 3;
}

/* ---- the daemon ---- */

bool hx_env_start(hx_env *env, const char *const *extra_args)
{
    fc_test_daemon_setup setup = {.extra_args = extra_args};
    return hx_env_start_with(env, &setup);
}

bool hx_env_start_with(hx_env *env, const fc_test_daemon_setup *setup)
{
    const char *args[MAX_DAEMON_ARGS + 1] = {"--log-level", "warn"};
    int n = 2;
    env->tls = NULL;
    if (hx_tls_requested() && !(env->tls = hx_tls_create()))
        return false;   /* never the plaintext matrix in place of the TLS one */
    if (env->tls) {
        printf("hardening: every connection through TLS 1.3 (certificate %s)\n", hx_tls_cert_path(env->tls));
        args[n++] = "--tls-cert";
        args[n++] = hx_tls_cert_path(env->tls);
        args[n++] = "--tls-key";
        args[n++] = hx_tls_key_path(env->tls);
    }
    for (int i = 0; setup->extra_args && setup->extra_args[i] && n < MAX_DAEMON_ARGS; i++)
        args[n++] = setup->extra_args[i];
    args[n] = NULL;
    fc_test_daemon_setup with_args = *setup;
    with_args.extra_args = args;
    fc_error err;
    env->witness_fd = -1;
    env->witness_next_id = WITNESS_FIRST_ID;
    if (fc_test_daemon_start_with(&env->daemon, &with_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        CHECK_MSG(0, "cannot start the daemon: %s", err.message);
        return false;
    }
    env->witness_fd = hx_connect_greeted(env, 0);
    hx_expect_witness_served(env);
    return true;
}

void hx_env_stop(hx_env *env)
{
    hx_expect_witness_served(env);
    if (env->witness_fd >= 0)
        close(env->witness_fd);
    fc_error err;
    CHECK_MSG(fc_test_daemon_stop(&env->daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    hx_tls_destroy(env->tls);
    env->tls = NULL;
}

long long hx_daemon_status_kib(const hx_env *env, const char *field)
{
    char path[64], line[256];
    snprintf(path, sizeof path, "/proc/%d/status", (int)env->daemon.pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    size_t len = strlen(field);
    long long kib = -1;
    while (kib < 0 && fgets(line, sizeof line, f))
        if (strncmp(line, field, len) == 0 && line[len] == ':')
            kib = strtoll(line + len + 1, NULL, 10);
    fclose(f);
    return kib;
}

int hx_daemon_open_fds(const hx_env *env)
{
    char path[64];
    snprintf(path, sizeof path, "/proc/%d/fd", (int)env->daemon.pid);
    DIR *dir = opendir(path);
    if (!dir)
        return -1;
    int count = 0;
    for (struct dirent *entry = readdir(dir); entry; entry = readdir(dir))
        if (entry->d_name[0] != '.')
            count++;
    closedir(dir);
    return count;
}

bool hx_wait_daemon_fds_at_most(const hx_env *env, int count, int timeout_ms)
{
    double deadline = hx_now_ms() + timeout_ms;
    for (;;) {
        int open_fds = hx_daemon_open_fds(env);
        if (open_fds >= 0 && open_fds <= count)
            return true;
        if (hx_now_ms() >= deadline)
            return false;
        hx_sleep_ms(20);
    }
}

/* ---- the runner ---- */

static int open_for_case(hx_env *env, const hx_case *c)
{
    if (c->prologue == HX_RAW)
        return hx_connect(env);
    int fd = hx_connect_greeted(env, c->prologue == HX_GREETED ? 0 : FC_CAPS_ALL);
    if (fd >= 0 && c->prologue == HX_PUBLISHING)
        hx_publish(fd, c->name);
    return fd;
}

/* The reply the case's bytes must get, if any. */
static void expect_reply(int fd, const hx_case *c)
{
    if (c->expected == FC_ERR_BAD_MAGIC)
        hx_expect_error(fd, 0, c->expected);   /* nothing in the header can be trusted, not even its id */
    else if (c->expected != FC_OK)
        hx_expect_error(fd, HX_BAD_ID, c->expected);
    else if (c->prologue == HX_RAW && c->outcome == HX_STAYS_OPEN)
        hx_expect_reply_type(fd, HX_BAD_ID, FC_MSG_WELCOME);   /* an unusual but valid HELLO */
}

void hx_run_case_bytes(hx_env *env, const hx_case *c, const fc_buf *bytes)
{
    int failures_before = test_failures_;
    printf("case: %s\n", c->name);
    fflush(stdout);
    CHECK_MSG(!bytes->failed, "out of memory building the case");
    int fd = open_for_case(env, c);
    if (fd < 0)
        return;
    hx_send(fd, bytes->data, bytes->len);
    if (c->half_close)
        shutdown(fd, SHUT_WR);
    expect_reply(fd, c);
    /* While the offending connection is still open on our side. */
    hx_expect_witness_served(env);
    if (c->outcome == HX_STAYS_OPEN)
        hx_expect_renders(fd, 100);
    else
        hx_expect_closed(fd);
    close(fd);
    if (test_failures_ != failures_before)
        fprintf(stderr, "case '%s' failed\n", c->name);
}

void hx_run_case(hx_env *env, const hx_case *c)
{
    fc_buf bytes;
    fc_buf_init(&bytes);
    c->build(&bytes);
    hx_run_case_bytes(env, c, &bytes);
    fc_buf_free(&bytes);
}

void hx_run_cases(hx_env *env, const hx_case *cases, size_t count)
{
    for (size_t i = 0; i < count; i++)
        hx_run_case(env, &cases[i]);
}

int hx_exit_status(int main_status)
{
    return test_result() || main_status ? 1 : 0;
}
