/* test_daemon_errors.c — misbehaving clients against the real fluidcastd. Each
 * gets the exact error code echoing its request id; framing errors and errors
 * before HELLO close the connection, other errors leave it working; and after
 * every bad client a fresh well-behaved client is still served. */
#include <string.h>
#include <unistd.h>

#include "daemon_process.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "test_scene.h"
#include "test_util.h"

#define MAX_MESSAGE 1048576u

static const char *const daemon_args[] = {"--max-particles", "5000", "--max-image", "256x192",
                                          "--max-message", "1048576", NULL};

static int open_connection(uint16_t port)
{
    int fd = -1;
    fc_error err;
    CHECK_MSG(fc_test_connect(port, &fd, &err) == FC_OK, "%s", err.message);
    return fd;
}

static int greeted_connection(uint16_t port)
{
    int fd = open_connection(port);
    fc_welcome welcome;
    fc_error err;
    if (fd >= 0)
        CHECK_MSG(fc_test_handshake(fd, 1, &welcome, &err) == FC_OK, "%s", err.message);
    return fd;
}

static void send_bytes(int fd, const void *data, size_t size)
{
    fc_error err;
    CHECK_MSG(fc_test_send(fd, data, size, &err) == FC_OK, "%s", err.message);
}

static void send_buf(int fd, fc_buf *b)
{
    CHECK(!b->failed);
    send_bytes(fd, b->data, b->len);
    fc_buf_reset(b);
}

/* A raw header, written out byte by byte as PROTOCOL.md lays it out (little endian). */
static void raw_header(uint8_t out[16], const char *magic, uint16_t type, uint16_t flags, uint32_t request_id,
                       uint32_t length)
{
    memcpy(out, magic, 4);
    out[4] = (uint8_t)type;
    out[5] = (uint8_t)(type >> 8);
    out[6] = (uint8_t)flags;
    out[7] = (uint8_t)(flags >> 8);
    for (int i = 0; i < 4; i++) {
        out[8 + i] = (uint8_t)(request_id >> (8 * i));
        out[12 + i] = (uint8_t)(length >> (8 * i));
    }
}

static void expect_error(int fd, uint32_t request_id, fc_code code)
{
    uint32_t got_id = 0;
    fc_error remote = {0}, err;
    if (fc_test_read_error(fd, &got_id, &remote, &err) != FC_OK) {
        CHECK_MSG(0, "expected ERROR %d for request %u: %s", code, request_id, err.message);
        return;
    }
    CHECK_MSG(got_id == request_id, "ERROR answers request %u, expected %u", got_id, request_id);
    CHECK_MSG(remote.code == code, "ERROR code %d (%s), expected %d", remote.code, remote.message, code);
    CHECK_MSG(remote.message[0] != '\0', "ERROR %d without a reason", code);
}

static void expect_closed(int fd)
{
    fc_error err;
    CHECK_MSG(fc_test_expect_closed(fd, FC_TEST_IO_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
}

/* A complete render on fd answers with an IMAGE. */
static void expect_renders(int fd, uint32_t request_id)
{
    fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
    fc_test_message reply;
    fc_error err;
    if (fc_test_render(fd, request_id, 32, 24, &request, &reply, &err) != FC_OK) {
        CHECK_MSG(0, "render %u: %s", request_id, err.message);
        return;
    }
    CHECK_MSG(reply.header.type == FC_MSG_IMAGE && reply.header.request_id == request_id + 2,
              "render %u answered by type %u for request %u", request_id, reply.header.type,
              reply.header.request_id);
    fc_test_message_free(&reply);
}

/* The daemon survived whatever came before: a new client is served in full. */
static void expect_new_client_served(uint16_t port)
{
    int fd = greeted_connection(port);
    if (fd < 0)
        return;
    expect_renders(fd, 9000);
    close(fd);
}

static void test_bad_magic_closes(uint16_t port)
{
    int fd = open_connection(port);
    static const char garbage[] = "GET / HTTP/1.1\r\nHost: fluidcast\r\n\r\n";
    send_bytes(fd, garbage, sizeof garbage - 1);
    expect_error(fd, 0, FC_ERR_BAD_MAGIC);
    expect_closed(fd);
    close(fd);
    expect_new_client_served(port);
}

static void test_oversized_length_closes(uint16_t port)
{
    int fd = greeted_connection(port);
    uint8_t header[16];
    raw_header(header, "FCST", FC_MSG_FRAME, 0, 7, MAX_MESSAGE + 1);
    send_bytes(fd, header, sizeof header);
    expect_error(fd, 7, FC_ERR_TOO_LARGE);
    expect_closed(fd);
    close(fd);
    expect_new_client_served(port);
}

static void test_frame_before_hello_closes(uint16_t port)
{
    int fd = open_connection(port);
    fc_buf out;
    fc_frame frame;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_test_cube_frame(&frame, &err), FC_OK);
    fc_wire_write_frame(&out, 9, &frame, &err);
    send_buf(fd, &out);
    expect_error(fd, 9, FC_ERR_BAD_STATE);
    expect_closed(fd);
    close(fd);
    fc_frame_free(&frame);
    fc_buf_free(&out);
    expect_new_client_served(port);
}

static void test_unsupported_versions_close(uint16_t port)
{
    int fd = open_connection(port);
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_hello hello = {2, 5, 0, "from the future", ""};
    fc_wire_write_hello(&out, 3, &hello, &err);
    send_buf(fd, &out);
    expect_error(fd, 3, FC_ERR_VERSION);
    expect_closed(fd);
    close(fd);
    fc_buf_free(&out);
    expect_new_client_served(port);
}

static void test_unknown_type_keeps_connection(uint16_t port)
{
    int fd = greeted_connection(port);
    uint8_t header[16];
    raw_header(header, "FCST", 77, 0, 11, 0);
    send_bytes(fd, header, sizeof header);
    expect_error(fd, 11, FC_ERR_UNKNOWN_TYPE);
    /* Nonzero flags: MALFORMED, yet the length is known, so the stream goes on. */
    uint8_t flagged[20];
    raw_header(flagged, "FCST", FC_MSG_GOODBYE, 1, 12, 4);
    memset(flagged + 16, 0, 4);
    send_bytes(fd, flagged, sizeof flagged);
    expect_error(fd, 12, FC_ERR_MALFORMED);
    expect_renders(fd, 13);
    close(fd);
    expect_new_client_served(port);
}

static void test_truncated_payloads_are_malformed(uint16_t port)
{
    int fd = greeted_connection(port);
    /* A CAMERA of 20 bytes where 48 are due. */
    uint8_t camera[16 + 20] = {0};
    raw_header(camera, "FCST", FC_MSG_CAMERA, 0, 21, 20);
    send_bytes(fd, camera, sizeof camera);
    expect_error(fd, 21, FC_ERR_MALFORMED);

    /* A FRAME whose last particle lacks its z: the header announces the short length honestly. */
    fc_buf out;
    fc_frame frame;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_test_cube_frame(&frame, &err), FC_OK);
    fc_wire_write_frame(&out, 22, &frame, &err);
    uint32_t short_length = (uint32_t)(out.len - 16 - 4);
    raw_header(out.data, "FCST", FC_MSG_FRAME, 0, 22, short_length);
    out.len -= 4;
    send_buf(fd, &out);
    expect_error(fd, 22, FC_ERR_MALFORMED);

    /* A RENDER one field short. */
    uint8_t render[16 + 8] = {0};
    raw_header(render, "FCST", FC_MSG_RENDER, 0, 23, 8);
    send_bytes(fd, render, sizeof render);
    expect_error(fd, 23, FC_ERR_MALFORMED);
    expect_renders(fd, 24);
    close(fd);
    fc_frame_free(&frame);
    fc_buf_free(&out);
    expect_new_client_served(port);
}

static void test_nan_position_is_invalid(uint16_t port)
{
    int fd = greeted_connection(port);
    fc_buf out;
    fc_frame frame;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_test_cube_frame(&frame, &err), FC_OK);
    fc_wire_write_frame(&out, 31, &frame, &err);
    /* FRAME payload: count u64, attributes u32, reserved u32, then x of particle 0: a quiet NaN. */
    static const uint8_t quiet_nan[4] = {0x00, 0x00, 0xc0, 0x7f};
    memcpy(out.data + 16 + 16, quiet_nan, 4);
    send_buf(fd, &out);
    expect_error(fd, 31, FC_ERR_INVALID_VALUE);
    /* The refused frame was not stored. */
    fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
    fc_wire_write_render(&out, 32, &request, &err);
    send_buf(fd, &out);
    expect_error(fd, 32, FC_ERR_BAD_STATE);
    expect_renders(fd, 33);
    close(fd);
    fc_frame_free(&frame);
    fc_buf_free(&out);
    expect_new_client_served(port);
}

static void test_render_before_frame_is_bad_state(uint16_t port)
{
    int fd = greeted_connection(port);
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
    fc_wire_write_render(&out, 41, &request, &err);
    send_buf(fd, &out);
    expect_error(fd, 41, FC_ERR_BAD_STATE);
    expect_renders(fd, 42);
    close(fd);
    fc_buf_free(&out);
}

static void test_limits(uint16_t port)
{
    int fd = greeted_connection(port);
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_camera camera;
    fc_test_front_camera(4096, 4096, &camera);
    fc_wire_write_camera(&out, 51, &camera, &err);
    send_buf(fd, &out);
    expect_error(fd, 51, FC_ERR_LIMIT);

    fc_frame many;
    CHECK_CODE(fc_frame_alloc(&many, 5001, 0, &err), FC_OK);
    for (size_t i = 0; i < 3 * 5001; i++)
        many.positions[i] = (float)(i % 97) * 0.01f;
    fc_wire_write_frame(&out, 52, &many, &err);
    send_buf(fd, &out);
    expect_error(fd, 52, FC_ERR_LIMIT);
    fc_frame_free(&many);
    expect_renders(fd, 53);
    close(fd);
    fc_buf_free(&out);
    expect_new_client_served(port);
}

static void test_invalid_values(uint16_t port)
{
    int fd = greeted_connection(port);
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    /* Depth is float data: PNG cannot carry it. */
    CHECK_CODE(fc_test_write_render_sequence(&out, 61, 32, 24,
                                             &(fc_render_request){FC_FORMAT_PNG, 0, FC_AOV_DEPTH}, &err),
               FC_OK);
    send_buf(fd, &out);
    expect_error(fd, 63, FC_ERR_INVALID_VALUE);

    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = -1.0f;
    fc_wire_write_settings(&out, 64, &settings, &err);
    send_buf(fd, &out);
    expect_error(fd, 64, FC_ERR_INVALID_VALUE);
    expect_renders(fd, 65);
    close(fd);
    fc_buf_free(&out);
}

/* Clients that vanish mid-message or before reading their IMAGE cost the daemon nothing. */
static void test_disconnects(uint16_t port)
{
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_render_request request = {FC_FORMAT_RAW, 0, FC_AOV_COLOR};
    CHECK_CODE(fc_test_write_render_sequence(&out, 71, 256, 192, &request, &err), FC_OK);

    int fd = greeted_connection(port);
    send_bytes(fd, out.data, out.len / 2);
    close(fd);

    fd = greeted_connection(port);
    send_bytes(fd, out.data, out.len);
    close(fd);

    fd = open_connection(port);
    send_bytes(fd, "FCS", 3);
    close(fd);
    fc_buf_free(&out);
    expect_new_client_served(port);
}

int main(void)
{
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, daemon_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start the daemon: %s\n", err.message);
        return 1;
    }
    uint16_t port = daemon.port;
    test_bad_magic_closes(port);
    test_oversized_length_closes(port);
    test_frame_before_hello_closes(port);
    test_unsupported_versions_close(port);
    test_unknown_type_keeps_connection(port);
    test_truncated_payloads_are_malformed(port);
    test_nan_position_is_invalid(port);
    test_render_before_frame_is_bad_state(port);
    test_limits(port);
    test_invalid_values(port);
    test_disconnects(port);
    CHECK_MSG(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    return test_result();
}
