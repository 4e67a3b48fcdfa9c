/* test_client_scene.c — libfluidcast's scene images against the real
 * fluidcastd: a solid background fills the corners and an empty one brings
 * the built-in scene back exactly; a rejected image (undecodable, too large,
 * faces that do not match) is reported by the next render with its code and
 * leaves the previous image in place; local failures (a missing or empty
 * file) send nothing and keep the connection usable. Colour renders come back
 * RAW (RGBA8 rows), so pixels are read without any decoder. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "image_encoder.h"
#include "scene_fixtures.h"
#include "support/daemon_process.h"
#include "test_ball.h"
#include "test_util.h"

#define WIDTH 48
#define HEIGHT 36

typedef struct rgba_image {
    fc_image_result result;   /* data: WIDTH x HEIGHT x RGBA8, top row first */
    fc_code code;
    fc_error err;
} rgba_image;

static fc_code send_ball(fc_client *client, fc_error *err)
{
    fc_frame ball = {0};
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

static void render_rgba(fc_client *client, rgba_image *img)
{
    fc_render_request request = {.format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_COLOR};
    img->code = fc_client_render(client, &request, &img->result, &img->err);
    if (img->code == FC_OK)
        CHECK(img->result.width == WIDTH && img->result.height == HEIGHT &&
              img->result.size == (size_t)WIDTH * HEIGHT * 4);
}

static const uint8_t *pixel(const rgba_image *img, uint32_t x, uint32_t y)
{
    return img->result.data + ((size_t)y * WIDTH + x) * 4;
}

static bool is_colour(const uint8_t *p, int r, int g, int b)
{
    return abs(p[0] - r) <= 2 && abs(p[1] - g) <= 2 && abs(p[2] - b) <= 2;
}

/* What the server renders without scene images, to compare the reset with. */
static void render_plain(fc_client *client, rgba_image *plain)
{
    render_rgba(client, plain);
    CHECK_MSG(plain->code == FC_OK, "%s", plain->err.message);
}

static void test_background_and_reset(fc_client *client, const rgba_image *plain)
{
    fc_error err;
    rgba_image framed, reset;
    CHECK_CODE(fc_client_set_background_bytes(client, png_magenta_4x4, png_magenta_4x4_size, &err), FC_OK);
    render_rgba(client, &framed);
    CHECK_MSG(framed.code == FC_OK, "%s", framed.err.message);
    if (framed.code == FC_OK) {
        CHECK(is_colour(pixel(&framed, 0, 0), 200, 40, 120));
        CHECK(is_colour(pixel(&framed, WIDTH - 1, HEIGHT - 1), 200, 40, 120));
        CHECK(!is_colour(pixel(&framed, WIDTH / 2, HEIGHT / 2), 200, 40, 120));
    }
    fc_image_result_free(&framed.result);

    CHECK_CODE(fc_client_set_background_file(client, NULL, &err), FC_OK);
    render_rgba(client, &reset);
    CHECK(reset.code == FC_OK && plain->code == FC_OK &&
          memcmp(reset.result.data, plain->result.data, plain->result.size) == 0);
    fc_image_result_free(&reset.result);
}

/* The rejection is the next render's error; the render after it shows the image sent before. */
static void expect_rejected_background(fc_client *client, const uint8_t *file, size_t size, fc_code expected)
{
    fc_error err;
    CHECK_CODE(fc_client_set_background_bytes(client, png_magenta_4x4, png_magenta_4x4_size, &err), FC_OK);
    CHECK_CODE(fc_client_set_background_bytes(client, file, size, &err), FC_OK);
    rgba_image refused, kept;
    render_rgba(client, &refused);
    CHECK_MSG(refused.code == expected, "got %d (%s), expected %d", refused.code, refused.err.message, expected);
    CHECK(strncmp(refused.err.message, "server: BACKGROUND", 18) == 0);
    CHECK(refused.result.data == NULL);
    render_rgba(client, &kept);
    CHECK_MSG(kept.code == FC_OK, "%s", kept.err.message);
    if (kept.code == FC_OK)
        CHECK(is_colour(pixel(&kept, 0, 0), 200, 40, 120));
    fc_image_result_free(&kept.result);
    CHECK_CODE(fc_client_set_background_bytes(client, NULL, 0, &err), FC_OK);
}

/* A 4x4 float EXR face, to mix with 8-bit ones. */
static bool encode_exr_face(fc_buf *out)
{
    float pixels[4 * 4 * 4];
    for (int i = 0; i < 4 * 4 * 4; i++)
        pixels[i] = 0.5f;
    fc_image face = {4, 4, 4, FC_PIXEL_F32, pixels, sizeof pixels};
    fc_error err;
    return fc_encode_image(&face, FC_FORMAT_EXR, 0, out, &err) == FC_OK;
}

static void expect_rejected_environment(fc_client *client, const void *const faces[6], const size_t sizes[6],
                                        const char *in_message)
{
    fc_error err;
    CHECK_CODE(fc_client_set_environment_bytes(client, faces, sizes, &err), FC_OK);
    rgba_image refused;
    render_rgba(client, &refused);
    CHECK_MSG(refused.code == FC_ERR_INVALID_VALUE, "got %d (%s)", refused.code, refused.err.message);
    CHECK_MSG(strstr(refused.err.message, in_message) != NULL, "\"%s\" lacks \"%s\"", refused.err.message,
              in_message);
}

static void test_environment(fc_client *client, const rgba_image *plain)
{
    fc_error err;
    const void *faces[6];
    size_t sizes[6];
    for (int i = 0; i < 6; i++) {
        faces[i] = png_red_4x4;
        sizes[i] = png_red_4x4_size;
    }
    CHECK_CODE(fc_client_set_environment_bytes(client, faces, sizes, &err), FC_OK);
    rgba_image red;
    render_rgba(client, &red);
    CHECK_MSG(red.code == FC_OK, "%s", red.err.message);
    /* A red sky shows in the fluid's reflection only: the background is untouched. */
    if (red.code == FC_OK && plain->code == FC_OK) {
        CHECK(memcmp(pixel(&red, 0, 0), pixel(plain, 0, 0), 4) == 0);
        CHECK(memcmp(red.result.data, plain->result.data, plain->result.size) != 0);
    }
    fc_image_result_free(&red.result);

    faces[4] = png_red_4x2;
    sizes[4] = png_red_4x2_size;
    expect_rejected_environment(client, faces, sizes, "+Z is 4x2, not square");
    faces[4] = png_blue_4x4;
    sizes[4] = png_blue_4x4_size;
    fc_buf exr;
    fc_buf_init(&exr);
    CHECK(encode_exr_face(&exr));
    faces[5] = exr.data;
    sizes[5] = exr.len;
    expect_rejected_environment(client, faces, sizes, "-Z is float but face +X is 8-bit");
    fc_buf_free(&exr);
    faces[5] = not_an_image;
    sizes[5] = not_an_image_size;
    expect_rejected_environment(client, faces, sizes, "face -Z: not a PNG, JPEG or EXR image");

    CHECK_CODE(fc_client_set_environment_bytes(client, NULL, NULL, &err), FC_OK);
    rgba_image reset;
    render_rgba(client, &reset);
    CHECK(reset.code == FC_OK && plain->code == FC_OK &&
          memcmp(reset.result.data, plain->result.data, plain->result.size) == 0);
    fc_image_result_free(&reset.result);
}

/* Failures found before sending: nothing reaches the server, the connection goes on. */
static void test_local_failures(fc_client *client)
{
    char empty[] = "/tmp/fluidcast-scene-empty-XXXXXX";
    int fd = mkstemp(empty);
    CHECK(fd >= 0);
    if (fd >= 0)
        close(fd);
    fc_error err;
    CHECK_CODE(fc_client_set_background_file(client, "/nonexistent/bg.png", &err), FC_ERR_IO);
    CHECK(strstr(err.message, "/nonexistent/bg.png") != NULL);
    CHECK_CODE(fc_client_set_background_file(client, empty, &err), FC_ERR_USAGE);
    const char *paths[6] = {empty, empty, empty, empty, empty, "/nonexistent/nz.png"};
    CHECK_CODE(fc_client_set_environment_files(client, paths, &err), FC_ERR_USAGE);
    const void *faces[6] = {png_red_4x4, png_red_4x4, png_red_4x4, png_red_4x4, png_red_4x4, NULL};
    const size_t sizes[6] = {png_red_4x4_size, png_red_4x4_size, png_red_4x4_size, png_red_4x4_size,
                             png_red_4x4_size, 0};
    CHECK_CODE(fc_client_set_environment_bytes(client, faces, sizes, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_client_set_background_bytes(client, NULL, 10, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_client_set_background_bytes(NULL, NULL, 0, &err), FC_ERR_USAGE);
    unlink(empty);
    rgba_image after;
    render_rgba(client, &after);
    CHECK_MSG(after.code == FC_OK, "%s", after.err.message);
    fc_image_result_free(&after.result);
}

int main(void)
{
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        return 1;
    }
    char address[32];
    snprintf(address, sizeof address, "127.0.0.1:%u", (unsigned)daemon.port);
    fc_client *client = NULL;
    CHECK_CODE(fc_client_connect(address, NULL, &client, &err), FC_OK);
    if (client && send_ball(client, &err) == FC_OK) {
        rgba_image plain;
        render_plain(client, &plain);
        test_background_and_reset(client, &plain);
        expect_rejected_background(client, not_an_image, not_an_image_size, FC_ERR_INVALID_VALUE);
        expect_rejected_background(client, png_black_8193x1, png_black_8193x1_size, FC_ERR_LIMIT);
        test_environment(client, &plain);
        test_local_failures(client);
        fc_image_result_free(&plain.result);
    }
    fc_client_close(client);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    return test_result();
}
