/* test_client_protocol.c — libfluidcast against a scripted fake server: the
 * handshake fields, an ERROR for an earlier FRAME reported by the next render
 * (and the stream still in step afterwards), refusing an oversized frame
 * unsent, and the error codes for garbage, early close, a refused HELLO, an
 * unreachable port and malformed addresses. */
#include <stdio.h>
#include <string.h>

#include "fake_server.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "test_util.h"

#define SCRIPT_CHECK(conn, cond)                                                   \
    do {                                                                           \
        if (!(cond)) {                                                             \
            fprintf(stderr, "%s:%d: server script: %s\n", __FILE__, __LINE__, #cond); \
            (conn)->failures++;                                                    \
            return;                                                                \
        }                                                                          \
    } while (0)
/* Reads the next message into *m (freeing what m held) and requires its type. */
#define SCRIPT_EXPECT(conn, type, m)                                               \
    do {                                                                           \
        fc_test_message_free(m);                                                   \
        SCRIPT_CHECK(conn, fake_expect(conn, type, m));                            \
    } while (0)

static const uint8_t second_image[] = { 0x89, 'P', 'N', 'G', 1, 2, 3 };

/* HELLO -> WELCOME; FRAME and RENDER -> ERROR for the FRAME, then an IMAGE the
 * client must discard; RENDER -> IMAGE; RENDER -> ERROR; then GOODBYE must be
 * next: the oversized frame the client refused must never arrive. */
static void script_session(fake_connection *conn)
{
    fc_test_message m = { 0 };
    SCRIPT_EXPECT(conn, FC_MSG_HELLO, &m);
    fc_hello hello;
    SCRIPT_CHECK(conn, fc_wire_read_hello(m.payload, m.header.length, &hello, NULL) == FC_OK);
    SCRIPT_CHECK(conn, hello.version_min == 1 && hello.version_max == 1);
    SCRIPT_CHECK(conn, strcmp(hello.client_name, "protocol-test") == 0);
    SCRIPT_CHECK(conn, fake_welcome(conn, m.header.request_id));

    SCRIPT_EXPECT(conn, FC_MSG_FRAME, &m);
    uint32_t frame_id = m.header.request_id;
    SCRIPT_EXPECT(conn, FC_MSG_RENDER, &m);
    uint32_t render_id = m.header.request_id;
    SCRIPT_CHECK(conn, render_id > frame_id);
    SCRIPT_CHECK(conn, fake_error(conn, frame_id, FC_ERR_INVALID_VALUE, "particle 3 has a NaN position"));
    static const uint8_t first_image[] = { 1, 1, 1 };
    SCRIPT_CHECK(conn, fake_image(conn, render_id, first_image, sizeof first_image));

    SCRIPT_EXPECT(conn, FC_MSG_RENDER, &m);
    SCRIPT_CHECK(conn, fake_image(conn, m.header.request_id, second_image, sizeof second_image));

    SCRIPT_EXPECT(conn, FC_MSG_RENDER, &m);
    SCRIPT_CHECK(conn, fake_error(conn, m.header.request_id, FC_ERR_LIMIT, "image 9999x9999 exceeds 640x480"));

    SCRIPT_EXPECT(conn, FC_MSG_GOODBYE, &m);
    fc_test_message_free(&m);
}

static char address[64];

static const char *fake_address(const fake_server *s)
{
    snprintf(address, sizeof address, "127.0.0.1:%u", (unsigned)fake_server_port(s));
    return address;
}

static void test_session(void)
{
    fake_server *server = fake_server_start(script_session);
    CHECK(server != NULL);
    if (!server)
        return;
    fc_connect_options options = { .client_name = "protocol-test", .reply_timeout_ms = 10000 };
    fc_client *client = NULL;
    fc_error err;
    CHECK_CODE(fc_client_connect(fake_address(server), &options, &client, &err), FC_OK);
    if (client) {
        fc_server_info info;
        fc_client_server_info(client, &info);
        CHECK(info.protocol_version == 1);
        CHECK(strcmp(info.server_version, FAKE_SERVER_VERSION) == 0);
        CHECK(strcmp(info.renderer, FAKE_RENDERER) == 0);
        CHECK(info.max_particles == 1000 && info.max_width == 640 && info.max_height == 480);
        CHECK(info.max_message == 4096);

        float positions[3] = { 0.0f, 1.0f, 2.0f };
        fc_frame frame = { .count = 1, .positions = positions };
        CHECK_CODE(fc_client_send_frame(client, &frame, &err), FC_OK);

        fc_render_request request = { .format = FC_FORMAT_PNG, .quality = 90, .aov = FC_AOV_COLOR };
        fc_image_result image;
        CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_ERR_INVALID_VALUE);
        CHECK(strcmp(err.message, "server: particle 3 has a NaN position") == 0);
        CHECK(image.data == NULL && image.size == 0);

        CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_OK);
        CHECK(image.size == sizeof second_image);
        CHECK(image.data && memcmp(image.data, second_image, sizeof second_image) == 0);
        CHECK(image.width == 4 && image.height == 3 && image.format == FC_FORMAT_PNG);
        CHECK_NEAR(image.stage_ms[FC_STAGE_TOTAL], FC_STAGE_TOTAL + 0.5, 1e-6);
        fc_image_result_free(&image);
        CHECK(image.data == NULL);

        CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_ERR_LIMIT);
        CHECK(strncmp(err.message, "server: ", 8) == 0);

        /* 400 particles * 12 bytes > the fake's 4096-byte message limit. */
        float big_positions[3 * 400] = { 0 };
        fc_frame big = { .count = 400, .positions = big_positions };
        CHECK_CODE(fc_client_send_frame(client, &big, &err), FC_ERR_TOO_LARGE);
        fc_client_close(client);
    }
    CHECK_CODE(fake_server_finish(server), 0);
}

static void script_garbage(fake_connection *conn)
{
    fc_test_message m = { 0 };
    SCRIPT_EXPECT(conn, FC_MSG_HELLO, &m);
    fc_test_message_free(&m);
    static const char garbage[] = "HTTP/1.1 400 Bad Request\r\n\r\n";
    SCRIPT_CHECK(conn, fc_test_send(conn->fd, garbage, sizeof garbage - 1, NULL) == FC_OK);
}

static void script_close_after_hello(fake_connection *conn)
{
    fc_test_message m = { 0 };
    SCRIPT_EXPECT(conn, FC_MSG_HELLO, &m);
    fc_test_message_free(&m);
}

static void script_refuse_hello(fake_connection *conn)
{
    fc_test_message m = { 0 };
    SCRIPT_EXPECT(conn, FC_MSG_HELLO, &m);
    fc_test_message_free(&m);
    SCRIPT_CHECK(conn, fake_error(conn, m.header.request_id, FC_ERR_VERSION, "speaks versions 2..3"));
}

/* Welcomes, then hangs up on the first request after it. */
static void script_close_on_render(fake_connection *conn)
{
    fc_test_message m = { 0 };
    SCRIPT_EXPECT(conn, FC_MSG_HELLO, &m);
    SCRIPT_CHECK(conn, fake_welcome(conn, m.header.request_id));
    SCRIPT_EXPECT(conn, FC_MSG_RENDER, &m);
    fc_test_message_free(&m);
}

static fc_code connect_to_script(fake_script script, fc_error *err)
{
    fake_server *server = fake_server_start(script);
    CHECK(server != NULL);
    if (!server)
        return FC_ERR_INTERNAL;
    fc_connect_options options = { .connect_timeout_ms = 5000 };
    fc_client *client = NULL;
    fc_code code = fc_client_connect(fake_address(server), &options, &client, err);
    CHECK(code == FC_OK ? client != NULL : client == NULL);
    fc_client_close(client);
    CHECK_CODE(fake_server_finish(server), 0);
    return code;
}

static void test_handshake_failures(void)
{
    fc_error err;
    CHECK_CODE(connect_to_script(script_garbage, &err), FC_ERR_PROTOCOL);
    CHECK_CODE(connect_to_script(script_close_after_hello, &err), FC_ERR_CLOSED);
    CHECK_CODE(connect_to_script(script_refuse_hello, &err), FC_ERR_VERSION);
    CHECK(strcmp(err.message, "server: speaks versions 2..3") == 0);
}

static void test_connection_lost_during_render(void)
{
    fake_server *server = fake_server_start(script_close_on_render);
    CHECK(server != NULL);
    if (!server)
        return;
    fc_client *client = NULL;
    fc_error err;
    CHECK_CODE(fc_client_connect(fake_address(server), NULL, &client, &err), FC_OK);
    fc_render_request request = { .format = FC_FORMAT_PNG, .quality = 90, .aov = FC_AOV_COLOR };
    fc_image_result image;
    CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_ERR_CLOSED);
    /* The connection is gone: later requests fail at once, without a send. */
    fc_camera cam = { .eye = { 0, -1, 0 }, .up = { 0, 0, 1 }, .fov_y_deg = 40, .width = 8, .height = 8 };
    CHECK_CODE(fc_client_set_camera(client, &cam, &err), FC_ERR_CLOSED);
    fc_client_close(client);
    CHECK_CODE(fake_server_finish(server), 0);
}

static void test_address_errors(void)
{
    fc_client *client = (fc_client *)&client;   /* must be reset to NULL on failure */
    fc_error err;
    char refused[32];
    snprintf(refused, sizeof refused, "127.0.0.1:%u", (unsigned)fake_unused_port());
    CHECK_CODE(fc_client_connect(refused, NULL, &client, &err), FC_ERR_CONNECT);
    CHECK(client == NULL);
    const char *malformed[] = { "localhost:http", "localhost:0", "localhost:65536", "[::1", "[::1]x",
                                ":7450", "", "host:", "host:+80", "::1", "fe80::1:7450" };
    for (size_t i = 0; i < sizeof malformed / sizeof malformed[0]; i++) {
        fc_code code = fc_client_connect(malformed[i], NULL, &client, &err);
        CHECK_MSG(code == FC_ERR_USAGE, "\"%s\" gave code %d", malformed[i], (int)code);
    }
    CHECK_CODE(fc_client_connect("no-such-host.invalid:7450", NULL, &client, &err), FC_ERR_CONNECT);
}

int main(void)
{
    test_session();
    test_handshake_failures();
    test_connection_lost_during_render();
    test_address_errors();
    return test_result();
}
