/* ball_png.c — the scene the container tests render through a containerised
 * fluidcastd, and the check of what comes back. The scene is the integration
 * tests' analytic ball (tests/integration/test_ball.h), seen from -y; the
 * shell test renders it with the host's fluidcast CLI:
 *
 *     fc_container_ball write DIR                 DIR/ball.f32 and DIR/corners.f32
 *     fluidcast snapshot DIR/ball.f32 -o ball.png --size 160x120 --eye 0,-4,0 --target 0,0,0 --radius 0.05
 *     (and the same for corners.f32 -> empty.png: same bounds, so the same floor and sky, no ball)
 *     fc_container_ball check ball.png empty.png  exit 0 when the pixels show the ball
 *
 * The check decodes both PNGs with OpenImageIO (not the daemon's encoder):
 * fluid covers the centre (far from the background there), the ring 45 px out
 * is the empty scene's background. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_runner.h"
#include "fc_frame.h"
#include "support/image_decode.h"
#include "test_ball.h"
#include "test_util.h"
#include "tinted_look.h"

#define WIDTH 160
#define HEIGHT 120

static int write_scene(const char *dir)
{
    char ball_path[512], corners_path[512];
    snprintf(ball_path, sizeof ball_path, "%s/ball.f32", dir);
    snprintf(corners_path, sizeof corners_path, "%s/corners.f32", dir);
    fc_frame ball = {0}, corners = {0};
    fc_error err = {0};
    bool ok = test_ball_frame(&ball, &err) == FC_OK && test_ball_box_corners(&corners, &err) == FC_OK &&
              test_write_f32(&ball, ball_path) && test_write_f32(&corners, corners_path);
    fc_frame_free(&ball);
    fc_frame_free(&corners);
    if (!ok)
        fprintf(stderr, "fc_container_ball: cannot write the scene into %s: %s\n", dir, err.message);
    return ok ? 0 : 1;
}

static bool decode(const char *path, fc_decoded_image *out)
{
    size_t size;
    uint8_t *data = read_whole_file(path, &size);
    fc_error err = {0};
    fc_code code = data ? fc_decode_image(data, size, "png", 0, out, &err) : FC_ERR_IO;
    CHECK_MSG(code == FC_OK, "decoding %s: %s", path, data ? err.message : "unreadable");
    free(data);
    return code == FC_OK;
}

static int colour_distance(const fc_decoded_image *a, const fc_decoded_image *b, uint32_t x, uint32_t y)
{
    const uint8_t *p = (const uint8_t *)a->pixels + ((size_t)y * a->width + x) * a->channels;
    const uint8_t *q = (const uint8_t *)b->pixels + ((size_t)y * b->width + x) * b->channels;
    return abs(p[0] - q[0]) + abs(p[1] - q[1]) + abs(p[2] - q[2]);
}

static int check_images(const char *ball_path, const char *empty_path)
{
    fc_decoded_image ball, empty;
    if (!decode(ball_path, &ball))
        return test_result();
    if (decode(empty_path, &empty)) {
        CHECK_MSG(ball.width == WIDTH && ball.height == HEIGHT && ball.channels >= 3, "ball.png is %ux%u x%u",
                  ball.width, ball.height, ball.channels);
        CHECK(empty.width == WIDTH && empty.height == HEIGHT && empty.channels >= 3);
        if (test_result() == 0) {
            const uint32_t cx = WIDTH / 2, cy = HEIGHT / 2;
            CHECK_MSG(colour_distance(&ball, &empty, cx, cy) > 30,
                      "no fluid at the centre");
            for (int d = -8; d <= 8; d += 4)
                CHECK_MSG(colour_distance(&ball, &empty, cx + d, cy + d) > 30, "no fluid at offset %d", d);
            const uint32_t outside[][2] = {{cx - 45, cy}, {cx + 45, cy}, {cx, cy - 45}, {cx, cy + 45}, {0, 0},
                                           {WIDTH - 1, HEIGHT - 1}};
            for (size_t i = 0; i < sizeof outside / sizeof outside[0]; i++)
                CHECK_MSG(colour_distance(&ball, &empty, outside[i][0], outside[i][1]) <= 6,
                          "pixel %u,%u is not background", outside[i][0], outside[i][1]);
        }
        fc_decoded_image_free(&empty);
    }
    fc_decoded_image_free(&ball);
    if (test_result() == 0)
        printf("%s: fluid at the centre, background around it\n", ball_path);
    return test_result();
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "write") == 0)
        return write_scene(argv[2]);
    if (argc == 4 && strcmp(argv[1], "check") == 0)
        return check_images(argv[2], argv[3]);
    if (argc == 2 && strcmp(argv[1], "absorption") == 0) {
        /* check finds the ball by its colour: the renders ask for the tinted look. */
        puts(TINTED_LOOK_ABSORPTION);
        return 0;
    }
    fprintf(stderr, "usage: %s write DIR | check BALL.png EMPTY.png | absorption\n", argv[0]);
    return 2;
}
