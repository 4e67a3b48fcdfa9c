/* test_hardening_clients.c — clients that misbehave in time rather than in
 * content, against the real fluidcastd: one that sends a byte at a time, one
 * that never reads its images, ones that vanish mid-upload or mid-render, a
 * burst of 1000 connections opened and dropped, and a flood of pipelined bad
 * messages. Throughout, a witness client must be served correctly, and
 * afterwards the daemon must hold no more descriptors than before.
 *
 * The daemon runs with a short --read-timeout-ms: a slow client whose messages
 * each complete in time is served, one that stalls mid-message is cut off. */
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <arpa/inet.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fc_error.h"
#include "hardening_harness.h"
#include "test_scene.h"
#include "test_util.h"

#define BURST_CONNECTIONS 1000
#define BURST_BATCH 100
#define FDS_SETTLE_MS 15000
#define PIPELINED_ERRORS 200
#define UNREAD_RENDERS 8
#define UNREAD_SIDE 256u

/* Long enough for a byte-at-a-time FRAME on a loaded machine under AddressSanitizer. */
#define READ_TIMEOUT_MS 3000

static const char *const daemon_args[] = {"--max-image", "256x256", "--read-timeout-ms", "3000", NULL};

static void set_int_option(int fd, int level, int name, int value)
{
    CHECK_MSG(setsockopt(fd, level, name, &value, sizeof value) == 0, "setsockopt %d", name);
}

/* A connection whose receive buffer is as small as the kernel allows, so
 * unread replies back up into the daemon quickly. */
static int connect_with_small_receive_buffer(const hx_env *env)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    CHECK(fd >= 0);
    if (fd < 0)
        return -1;
    set_int_option(fd, SOL_SOCKET, SO_RCVBUF, 4096);
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_port = htons(env->daemon.port)};
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    CHECK(connect(fd, (struct sockaddr *)&addr, sizeof addr) == 0);
    return fd;
}

/* Closing with SO_LINGER 0 sends a reset instead of an orderly FIN. */
static void close_with_reset(int fd)
{
    struct linger hard = {1, 0};
    setsockopt(fd, SOL_SOCKET, SO_LINGER, &hard, sizeof hard);
    close(fd);
}

static void expect_fds_back_to(const hx_env *env, int baseline, const char *after)
{
    CHECK_MSG(hx_wait_daemon_fds_at_most(env, baseline, FDS_SETTLE_MS),
              "after %s the daemon holds %d descriptors, %d before", after, hx_daemon_open_fds(env), baseline);
}

/* Every byte of a render sequence in its own segment, with the witness served
 * while the slow client sits inside a header and inside a payload. */
static void test_byte_at_a_time(hx_env *env)
{
    printf("case: a client sending one byte at a time\n");
    int fd = hx_connect_greeted(env, 0);
    if (fd < 0)
        return;
    set_int_option(fd, IPPROTO_TCP, TCP_NODELAY, 1);
    fc_buf out;
    fc_buf_init(&out);
    hx_write_render_sequence(&out, 100);
    for (size_t i = 0; i < out.len; i++) {
        hx_send(fd, out.data + i, 1);
        if (i % 8 == 7)
            hx_sleep_ms(1);
        if (i == 7 || i == 16 + 40 || i == out.len / 2)
            hx_expect_witness_served(env);
    }
    fc_buf_free(&out);
    hx_expect_cube_image(fd, 102);
    hx_expect_witness_served(env);
    close(fd);
}

/* A message that stops arriving: ERROR LIMIT for request 0 (the message never
 * completed) once the read timeout has passed, not before, then the close. */
static void test_stalled_mid_message(hx_env *env, int baseline)
{
    printf("case: a client that stalls mid-message\n");
    int fd = hx_connect_greeted(env, 0);
    if (fd < 0)
        return;
    fc_buf out;
    fc_buf_init(&out);
    hx_write_render_sequence(&out, 100);
    double start = hx_now_ms();
    hx_send(fd, out.data, FC_WIRE_HEADER_SIZE + 4);
    fc_buf_free(&out);
    hx_expect_witness_served(env);
    hx_expect_error(fd, 0, FC_ERR_LIMIT);
    double waited = hx_now_ms() - start;
    CHECK_MSG(waited >= READ_TIMEOUT_MS - 50, "cut off after %.0f ms, the read timeout is %d ms", waited,
              READ_TIMEOUT_MS);
    hx_expect_closed(fd);
    close(fd);
    hx_expect_witness_served(env);
    expect_fds_back_to(env, baseline, "a stalled client");
}

static void send_unread_renders(int fd)
{
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    hx_hello(&out, 1, 1, 1, 0);
    hx_write_render_sequence(&out, 100);
    fc_camera big;
    fc_test_front_camera(UNREAD_SIDE, UNREAD_SIDE, &big);
    CHECK_CODE(fc_wire_write_camera(&out, 103, &big, &err), FC_OK);
    fc_render_request colour = {FC_FORMAT_RAW, 0, FC_AOV_COLOR};
    for (uint32_t i = 0; i < UNREAD_RENDERS; i++)
        CHECK_CODE(fc_wire_write_render(&out, 200 + i, &colour, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
}

/* Replies back up behind a client that does not read: the daemon must go on
 * serving others, lose nothing for the slow reader once it reads, and forget
 * everything when it leaves without reading. */
static void test_clients_that_do_not_read(hx_env *env, int baseline)
{
    printf("case: a client that reads its images late\n");
    int late = connect_with_small_receive_buffer(env);
    send_unread_renders(late);
    hx_sleep_ms(200);
    hx_expect_witness_served(env);
    hx_expect_reply_type(late, 1, FC_MSG_WELCOME);
    hx_expect_cube_image(late, 102);
    for (uint32_t i = 0; i < UNREAD_RENDERS; i++) {
        fc_test_message m;
        fc_error err;
        CHECK_CODE(fc_test_read_message(late, FC_TEST_IO_TIMEOUT_MS, &m, &err), FC_OK);
        CHECK_MSG(m.header.type == FC_MSG_IMAGE && m.header.request_id == 200 + i, "reply %u: type %u, request %u",
                  i, m.header.type, m.header.request_id);
        CHECK_MSG(m.header.length > (uint64_t)UNREAD_SIDE * UNREAD_SIDE * 4, "IMAGE of %u bytes", m.header.length);
        fc_test_message_free(&m);
    }
    close(late);

    printf("case: a client that never reads its images\n");
    int never = connect_with_small_receive_buffer(env);
    send_unread_renders(never);
    hx_sleep_ms(200);
    hx_expect_witness_served(env);
    close(never);
    hx_expect_witness_served(env);
    expect_fds_back_to(env, baseline, "clients that did not read");
}

/* Half a render sequence, then gone: orderly close, reset, and gone while its RENDER renders. */
static void test_disconnects_mid_upload(hx_env *env, int baseline)
{
    fc_buf out;
    fc_buf_init(&out);
    hx_write_render_sequence(&out, 100);

    printf("case: disconnect mid-upload\n");
    int fd = hx_connect_greeted(env, 0);
    hx_send(fd, out.data, out.len / 2);
    close(fd);
    hx_expect_witness_served(env);

    printf("case: reset mid-upload\n");
    fd = hx_connect_greeted(env, 0);
    hx_send(fd, out.data, out.len / 3);
    close_with_reset(fd);
    hx_expect_witness_served(env);

    printf("case: disconnect while the RENDER renders\n");
    fd = hx_connect_greeted(env, 0);
    hx_send(fd, out.data, out.len);
    close_with_reset(fd);
    hx_expect_witness_served(env);

    fc_buf_free(&out);
    expect_fds_back_to(env, baseline, "disconnects mid-upload");
}

/* What each connection of the burst does before it is dropped. */
static void misbehave_briefly(int fd, int n)
{
    static const uint8_t hello_start[] = {'F', 'C', 'S', 'T', 1, 0, 0, 0, 1};
    if (n % 3 == 1)
        hx_send(fd, "FCS", 3);
    else if (n % 3 == 2)
        hx_send(fd, hello_start, sizeof hello_start);
    if (n % 2)
        close_with_reset(fd);
    else
        close(fd);
}

static void test_thousand_connections(hx_env *env, int baseline)
{
    printf("case: %d connections opened and dropped\n", BURST_CONNECTIONS);
    double start = hx_now_ms();
    int fds[BURST_BATCH];
    for (int opened = 0; opened < BURST_CONNECTIONS; opened += BURST_BATCH) {
        for (int i = 0; i < BURST_BATCH; i++)
            fds[i] = hx_connect(env);
        for (int i = 0; i < BURST_BATCH; i++)
            if (fds[i] >= 0)
                misbehave_briefly(fds[i], opened + i);
    }
    hx_expect_witness_served(env);
    double elapsed = hx_now_ms() - start;
    printf("%d connections opened and dropped, witness served: %.0f ms\n", BURST_CONNECTIONS, elapsed);
    expect_fds_back_to(env, baseline, "the burst of connections");
    int fd = hx_connect_greeted(env, 0);
    hx_expect_renders(fd, 100);
    close(fd);
}

/* Many bad messages in one write: every one answered, in order, with the
 * witness served while the replies wait unread. */
static void test_pipelined_errors(hx_env *env)
{
    printf("case: %d pipelined unknown messages\n", PIPELINED_ERRORS);
    int fd = hx_connect_greeted(env, 0);
    fc_buf out;
    fc_buf_init(&out);
    for (uint32_t i = 0; i < PIPELINED_ERRORS; i++) {
        hx_header(&out, 77, 0, 1000 + i, 4);
        hx_u32(&out, i);
    }
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_witness_served(env);
    for (uint32_t i = 0; i < PIPELINED_ERRORS; i++)
        hx_expect_error(fd, 1000 + i, FC_ERR_UNKNOWN_TYPE);
    hx_expect_renders(fd, 100);
    close(fd);
}

int main(void)
{
    hx_env env;
    if (!hx_env_start(&env, daemon_args))
        return hx_exit_status(test_result());
    int baseline = hx_daemon_open_fds(&env);
    CHECK_MSG(baseline > 0, "cannot count the daemon's descriptors in /proc");
    test_byte_at_a_time(&env);
    test_stalled_mid_message(&env, baseline);
    test_clients_that_do_not_read(&env, baseline);
    test_disconnects_mid_upload(&env, baseline);
    test_thousand_connections(&env, baseline);
    test_pipelined_errors(&env);
    hx_env_stop(&env);
    return hx_exit_status(test_result());
}
