/* test_daemon_requests.c — a well-behaved client against the real fluidcastd:
 * the handshake, renders in every format checked against what the scene must
 * look like, settings, the automatic camera, GOODBYE and a clean SIGTERM exit. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "daemon_process.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "image_decode.h"
#include "test_scene.h"
#include "test_util.h"
#include "tinted_look.h"

static const char *const daemon_args[] = {"--max-particles", "5000", "--max-image", "256x192",
                                          "--max-message", "1048576", NULL};

static int connect_and_greet(uint16_t port)
{
    int fd;
    fc_error err;
    fc_welcome welcome;
    CHECK_CODE(fc_test_connect(port, &fd, &err), FC_OK);
    if (fd >= 0)
        CHECK_MSG(fc_test_handshake(fd, 1, &welcome, &err) == FC_OK, "%s", err.message);
    return fd;
}

static void send_buf(int fd, fc_buf *b)
{
    fc_error err;
    CHECK_MSG(!b->failed && fc_test_send(fd, b->data, b->len, &err) == FC_OK, "send failed");
    fc_buf_reset(b);
}

static void expect_error(int fd, uint32_t request_id, fc_code code)
{
    uint32_t got_id = 0;
    fc_error remote = {0}, err;
    CHECK_MSG(fc_test_read_error(fd, &got_id, &remote, &err) == FC_OK, "%s", err.message);
    CHECK_MSG(got_id == request_id, "ERROR answers request %u, expected %u", got_id, request_id);
    CHECK_MSG(remote.code == code, "ERROR code %d (%s), expected %d", remote.code, remote.message, code);
}

/* Renders the cube and decodes the IMAGE reply's header into *image; returns the reply (payload owns data). */
static fc_test_message render(int fd, uint32_t request_id, uint32_t w, uint32_t h, fc_image_format format,
                              fc_aov aov, fc_image_reply *image)
{
    fc_render_request request = {format, 90, aov};
    fc_test_message reply = {0};
    fc_error err;
    memset(image, 0, sizeof *image);
    CHECK_MSG(fc_test_render(fd, request_id, w, h, &request, &reply, &err) == FC_OK, "%s", err.message);
    CHECK_MSG(reply.header.type == FC_MSG_IMAGE, "reply type %u", reply.header.type);
    CHECK(reply.header.request_id == request_id + 2);
    if (reply.header.type == FC_MSG_IMAGE)
        CHECK_MSG(fc_wire_read_image(reply.payload, reply.header.length, image, &err) == FC_OK, "%s", err.message);
    return reply;
}

static void test_welcome_describes_the_server(uint16_t port)
{
    int fd;
    fc_error err;
    fc_welcome w;
    CHECK_CODE(fc_test_connect(port, &fd, &err), FC_OK);
    CHECK_MSG(fc_test_handshake(fd, 41, &w, &err) == FC_OK, "%s", err.message);
    CHECK(w.version == 1);
    CHECK(w.limits.max_particles == 5000);
    CHECK(w.limits.max_width == 256 && w.limits.max_height == 192);
    CHECK(w.limits.max_message == 1048576);
    CHECK_MSG(strcmp(w.server_version, "fluidcastd 0.1.0") == 0, "server_version '%s'", w.server_version);
    /* --gpu software: Mesa names its software rasteriser in GL_RENDERER. */
    CHECK_MSG(strstr(w.renderer, "llvmpipe") != NULL, "renderer '%s'", w.renderer);

    /* A second HELLO is refused but the connection stays usable. */
    fc_buf out;
    fc_buf_init(&out);
    fc_hello hello = {1, 1, 0, "again", ""};
    fc_wire_write_hello(&out, 42, &hello, &err);
    send_buf(fd, &out);
    expect_error(fd, 42, FC_ERR_BAD_STATE);
    fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
    fc_wire_write_render(&out, 43, &request, &err);
    send_buf(fd, &out);
    expect_error(fd, 43, FC_ERR_BAD_STATE);

    /* GOODBYE: the server closes without another word. */
    fc_wire_write_goodbye(&out, 44, &err);
    send_buf(fd, &out);
    CHECK_MSG(fc_test_expect_closed(fd, FC_TEST_IO_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    fc_buf_free(&out);
    close(fd);
}

static int differs(const uint8_t *a, const uint8_t *b)
{
    return abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]) > 30;
}

/* The tests that find the fluid by its colour ask for water that absorbs
 * plainly (tinted_look.h): the default's shallow water is nearly clear. */
static void send_tinted_look(int fd, uint32_t request_id)
{
    fc_settings settings;
    fc_settings_default(&settings);
    const float tinted[3] = TINTED_LOOK_ABSORPTION_RGB;
    memcpy(settings.absorption, tinted, sizeof tinted);
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    CHECK_MSG(fc_wire_write_settings(&out, request_id, &settings, &err) == FC_OK, "%s", err.message);
    send_buf(fd, &out);
    fc_buf_free(&out);
}

static void test_png_shows_fluid_over_background(uint16_t port)
{
    int fd = connect_and_greet(port);
    send_tinted_look(fd, 99);
    fc_image_reply image;
    fc_test_message reply = render(fd, 100, 64, 48, FC_FORMAT_PNG, FC_AOV_COLOR, &image);
    CHECK(image.width == 64 && image.height == 48 && image.format == FC_FORMAT_PNG && image.aov == FC_AOV_COLOR);
    CHECK_MSG(image.stage_ms[FC_STAGE_ENCODE] >= 0.0f, "encode %g ms", image.stage_ms[FC_STAGE_ENCODE]);
    CHECK_MSG(image.stage_ms[FC_STAGE_TOTAL] >= image.stage_ms[FC_STAGE_ENCODE], "total %g ms, encode %g ms",
              image.stage_ms[FC_STAGE_TOTAL], image.stage_ms[FC_STAGE_ENCODE]);
    fc_decoded_image png;
    fc_error err;
    if (image.data &&
        fc_decode_image(image.data, image.size, "png", 0, &png, &err) == FC_OK) {
        CHECK(png.width == 64 && png.height == 48 && png.channels == 3);   /* opaque: written without alpha */
        const uint8_t *px = png.pixels;
        const uint8_t *centre = px + (24 * 64 + 32) * 3;
        const uint8_t *corner = px;
        CHECK_MSG(differs(centre, corner), "centre %d,%d,%d vs corner %d,%d,%d", centre[0], centre[1], centre[2],
                  corner[0], corner[1], corner[2]);
        fc_decoded_image_free(&png);
    } else {
        CHECK_MSG(0, "IMAGE is not a PNG: %s", err.message);
    }
    fc_test_message_free(&reply);
    close(fd);
}

/* Linear depth of the cube's front at the image centre, from a 1-channel EXR render. */
static float centre_depth(int fd, uint32_t request_id, float *corner)
{
    fc_image_reply image;
    fc_test_message reply = render(fd, request_id, 40, 30, FC_FORMAT_EXR, FC_AOV_DEPTH, &image);
    CHECK(image.aov == FC_AOV_DEPTH && image.format == FC_FORMAT_EXR);
    fc_decoded_image exr;
    fc_error err;
    float depth = -1.0f;
    *corner = -1.0f;
    if (image.data && fc_decode_image(image.data, image.size, "exr", 1, &exr, &err) == FC_OK) {
        CHECK(exr.width == 40 && exr.height == 30 && exr.channels == 1);
        CHECK_MSG(strcmp(exr.channel_names[0], "Z") == 0, "channel '%s'", exr.channel_names[0]);
        const float *z = exr.pixels;
        depth = z[15 * 40 + 20];
        *corner = z[0];
        fc_decoded_image_free(&exr);
    } else {
        CHECK_MSG(0, "IMAGE is not an EXR: %s", err.message);
    }
    fc_test_message_free(&reply);
    return depth;
}

/* The eye is 3 units from the cube centre and the front particles sit at
 * z = 0.25: with a radius about the 0.1 spacing the front surface lies 2.6..2.75
 * away. A larger radius brings it closer; no fluid reads 0. */
static void test_depth_matches_geometry_and_settings(uint16_t port)
{
    int fd = connect_and_greet(port);
    float corner;
    float auto_depth = centre_depth(fd, 200, &corner);
    CHECK_MSG(auto_depth > 2.6f && auto_depth < 2.75f, "centre depth %g", auto_depth);
    CHECK_MSG(corner == 0.0f, "corner depth %g", corner);

    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = 0.2f;
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_wire_write_settings(&out, 210, &settings, &err);
    send_buf(fd, &out);
    fc_buf_free(&out);
    float big_depth = centre_depth(fd, 220, &corner);
    /* Sphere of radius 0.2 around (0.05,0.05,0.25), hit on the axis: 3 - 0.25 - sqrt(0.2^2 - 2*0.05^2). */
    CHECK_NEAR(big_depth, 3.0 - 0.25 - 0.187083, 0.03);
    CHECK_MSG(big_depth < auto_depth, "radius 0.2: %g, auto: %g", big_depth, auto_depth);
    close(fd);
}

static void test_raw_colour_is_rgba8_rows(uint16_t port)
{
    int fd = connect_and_greet(port);
    send_tinted_look(fd, 299);
    fc_image_reply image;
    fc_test_message reply = render(fd, 300, 40, 30, FC_FORMAT_RAW, FC_AOV_COLOR, &image);
    CHECK_MSG(image.size == 40 * 30 * 4, "RAW size %llu", (unsigned long long)image.size);
    if (image.data && image.size == 40 * 30 * 4)
        CHECK(differs(image.data + (15 * 40 + 20) * 4, image.data));
    fc_test_message_free(&reply);

    /* JPEG of the same frame, for completeness of the formats. */
    reply = render(fd, 310, 40, 30, FC_FORMAT_JPEG, FC_AOV_COLOR, &image);
    CHECK(image.size > 3 && image.data && memcmp(image.data, "\xff\xd8\xff", 3) == 0);
    fc_test_message_free(&reply);
    close(fd);
}

/* Without a CAMERA the frame is framed at 1280x720, beyond this server's 256x192. */
static void test_default_camera_respects_the_limit(uint16_t port)
{
    int fd = connect_and_greet(port);
    fc_frame frame;
    fc_error err;
    fc_buf out;
    fc_buf_init(&out);
    CHECK_CODE(fc_test_cube_frame(&frame, &err), FC_OK);
    fc_wire_write_frame(&out, 400, &frame, &err);
    fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
    fc_wire_write_render(&out, 401, &request, &err);
    send_buf(fd, &out);
    expect_error(fd, 401, FC_ERR_LIMIT);
    fc_frame_free(&frame);
    fc_buf_free(&out);
    close(fd);
}

int main(void)
{
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, daemon_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start the daemon: %s\n", err.message);
        return 1;
    }
    test_welcome_describes_the_server(daemon.port);
    test_png_shows_fluid_over_background(daemon.port);
    test_depth_matches_geometry_and_settings(daemon.port);
    test_raw_colour_is_rgba8_rows(daemon.port);
    test_default_camera_respects_the_limit(daemon.port);

    /* SIGTERM with a client still connected: a clean exit all the same. */
    int idle = connect_and_greet(daemon.port);
    CHECK_MSG(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    if (idle >= 0)
        close(idle);
    return test_result();
}
