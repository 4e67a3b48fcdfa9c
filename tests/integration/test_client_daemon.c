/* test_client_daemon.c — libfluidcast against the real fluidcastd: the
 * WELCOME's limits as configured, a depth render whose centre matches the
 * ball's analytic front surface, a colour PNG of the requested size, a
 * rejected frame reported by the next render with the stream still in step,
 * and a clean GOODBYE (the daemon then exits 0). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "test_ball.h"
#include "test_util.h"

#define MAX_PARTICLES 3000
/* Odd sizes put the centre pixel on the view axis. */
#define WIDTH 81
#define HEIGHT 61

static const char *const daemon_args[] = { "--max-particles", "3000", "--max-image", "256x256", NULL };

static void check_server_info(fc_client *client)
{
    fc_server_info info;
    fc_client_server_info(client, &info);
    CHECK(info.protocol_version == 1);
    CHECK_MSG(strncmp(info.server_version, "fluidcastd", 10) == 0, "server version \"%s\"", info.server_version);
    CHECK(info.renderer[0] != '\0');
    CHECK(info.max_particles == MAX_PARTICLES);
    CHECK(info.max_width == 256 && info.max_height == 256);
    CHECK(info.max_message > 0);
}

static fc_code send_ball_scene(fc_client *client, fc_error *err)
{
    fc_frame ball = { 0 };
    fc_code code = test_ball_frame(&ball, err);
    if (code == FC_OK)
        code = fc_client_send_frame(client, &ball, err);
    fc_frame_free(&ball);
    fc_camera cam;
    test_ball_camera(WIDTH, HEIGHT, &cam);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = BALL_SPHERE_RADIUS;
    if (code == FC_OK)
        code = fc_client_set_camera(client, &cam, err);
    if (code == FC_OK)
        code = fc_client_set_settings(client, &settings, err);
    return code;
}

static float raw_depth_at(const fc_image_result *image, uint32_t x, uint32_t y)
{
    float value;
    memcpy(&value, image->data + 4 * ((size_t)y * image->width + x), sizeof value);
    return value;
}

static void test_depth_render(fc_client *client)
{
    fc_error err;
    CHECK_CODE(send_ball_scene(client, &err), FC_OK);
    fc_render_request request = { .format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_DEPTH };
    fc_image_result image;
    CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_OK);
    if (!image.data)
        return;
    CHECK(image.width == WIDTH && image.height == HEIGHT);
    CHECK(image.format == FC_FORMAT_RAW && image.aov == FC_AOV_DEPTH);
    CHECK(image.size == (size_t)WIDTH * HEIGHT * sizeof(float));
    if (image.size == (size_t)WIDTH * HEIGHT * sizeof(float)) {
        CHECK_NEAR(raw_depth_at(&image, WIDTH / 2, HEIGHT / 2), BALL_FRONT_DEPTH, 0.02 * BALL_FRONT_DEPTH);
        CHECK(raw_depth_at(&image, 0, 0) == 0.0f);
        CHECK(raw_depth_at(&image, WIDTH - 1, HEIGHT - 1) == 0.0f);
    }
    CHECK(image.stage_ms[FC_STAGE_TOTAL] >= 0.0f);
    fc_image_result_free(&image);
}

static void test_png_render(fc_client *client)
{
    fc_error err;
    fc_render_request request = { .format = FC_FORMAT_PNG, .quality = 0, .aov = FC_AOV_COLOR };
    fc_image_result image;
    CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_OK);
    if (!image.data)
        return;
    fc_decoded_image decoded;
    CHECK_CODE(fc_decode_image(image.data, image.size, "png", 0, &decoded, &err), FC_OK);
    CHECK(decoded.width == WIDTH && decoded.height == HEIGHT);
    fc_decoded_image_free(&decoded);
    fc_image_result_free(&image);
}

/* A NaN position is rejected when the FRAME arrives; the render after it must
 * report that, and the next render (after a good frame) must succeed: the
 * client consumed the stale reply instead of mistaking it for the new one. */
static void test_rejected_frame(fc_client *client)
{
    fc_error err;
    float positions[6] = { 0.0f, 0.0f, 0.0f, 0.0f, NAN, 0.0f };
    fc_frame bad = { .count = 2, .positions = positions };
    CHECK_CODE(fc_client_send_frame(client, &bad, &err), FC_OK);
    fc_render_request request = { .format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_DEPTH };
    fc_image_result image;
    CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strncmp(err.message, "server: ", 8) == 0, "message \"%s\"", err.message);
    CHECK(image.data == NULL);

    CHECK_CODE(send_ball_scene(client, &err), FC_OK);
    CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_OK);
    CHECK(image.size == (size_t)WIDTH * HEIGHT * sizeof(float));
    fc_image_result_free(&image);
}

static void test_too_many_particles(fc_client *client)
{
    fc_error err;
    fc_frame big = { 0 };
    CHECK_CODE(fc_frame_alloc(&big, MAX_PARTICLES + 1, 0, &err), FC_OK);
    for (uint64_t i = 0; i < 3 * big.count; i++)
        big.positions[i] = (float)(i % 97) * 0.01f;
    CHECK_CODE(fc_client_send_frame(client, &big, &err), FC_OK);
    fc_frame_free(&big);
    fc_render_request request = { .format = FC_FORMAT_PNG, .quality = 0, .aov = FC_AOV_COLOR };
    fc_image_result image;
    CHECK_CODE(fc_client_render(client, &request, &image, &err), FC_ERR_LIMIT);
    fc_image_result_free(&image);
}

int main(void)
{
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, daemon_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        return 1;
    }
    char address[32];
    snprintf(address, sizeof address, "127.0.0.1:%u", (unsigned)daemon.port);
    fc_connect_options options = { .client_name = "test_client_daemon", .reply_timeout_ms = 60000 };
    fc_client *client = NULL;
    CHECK_CODE(fc_client_connect(address, &options, &client, &err), FC_OK);
    if (client) {
        check_server_info(client);
        test_depth_render(client);
        test_png_render(client);
        test_rejected_frame(client);
        test_too_many_particles(client);
        fc_client_close(client);
    }
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    return test_result();
}
