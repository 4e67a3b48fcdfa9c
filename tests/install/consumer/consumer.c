/* consumer.c — a program outside the tree, built by tests/install against the
 * installed headers and library only (pkg-config or find_package): connects to
 * a fluidcastd, sends a ball of particles, frames it with the library's own
 * camera (proto code that must be inside libfluidcast), renders a PNG and
 * writes it.
 *
 *     fluidcast-install-consumer HOST:PORT OUT.png */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"

#define SIDE 24

static int fail(const char *what, const fc_error *err)
{
    fprintf(stderr, "consumer: %s: %s: %s\n", what, fc_code_name(err->code), err->message);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s HOST:PORT OUT.png\n", argv[0]);
        return 2;
    }
    fc_error err = {0};
    fc_frame frame = {0};
    if (fc_frame_alloc(&frame, (uint64_t)SIDE * SIDE * SIDE, 0, &err) != FC_OK)
        return fail("frame", &err);
    uint64_t n = 0;
    for (int i = 0; i < SIDE; i++)
        for (int j = 0; j < SIDE; j++)
            for (int k = 0; k < SIDE; k++) {
                float x = i - SIDE / 2.0f, y = j - SIDE / 2.0f, z = k - SIDE / 2.0f;
                if (sqrtf(x * x + y * y + z * z) > SIDE / 2.0f)
                    continue;
                frame.positions[3 * n] = x * 0.05f;
                frame.positions[3 * n + 1] = y * 0.05f;
                frame.positions[3 * n + 2] = z * 0.05f;
                n++;
            }
    frame.count = n;

    fc_camera camera;
    fc_camera_frame_bounds(&frame, 160, 120, &camera);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = fc_frame_estimate_radius(&frame);

    fc_connect_options options = {.client_name = "install consumer", .reply_timeout_ms = 60000};
    fc_client *c;
    if (fc_client_connect(argv[1], &options, &c, &err) != FC_OK)
        return fail("connect", &err);
    fc_image_result image = {0};
    fc_render_request request = {FC_FORMAT_PNG, 90, FC_AOV_COLOR};
    fc_code code = fc_client_send_frame(c, &frame, &err);
    if (code == FC_OK)
        code = fc_client_set_camera(c, &camera, &err);
    if (code == FC_OK)
        code = fc_client_set_settings(c, &settings, &err);
    if (code == FC_OK)
        code = fc_client_render(c, &request, &image, &err);
    fc_client_close(c);
    fc_frame_free(&frame);
    if (code != FC_OK)
        return fail("render", &err);

    static const unsigned char png_magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    int ok = image.size > sizeof png_magic && memcmp(image.data, png_magic, sizeof png_magic) == 0 &&
             image.width == 160 && image.height == 120;
    FILE *out = fopen(argv[2], "wb");
    if (out) {
        ok = ok && fwrite(image.data, 1, image.size, out) == image.size;
        ok = fclose(out) == 0 && ok;
    }
    if (!out || !ok) {
        fprintf(stderr, "consumer: no %ux%u PNG written to %s (%zu bytes)\n", 160u, 120u, argv[2], image.size);
        fc_image_result_free(&image);
        return 1;
    }
    printf("consumer: %llu particles, %ux%u PNG of %zu bytes in %s\n", (unsigned long long)n, image.width,
           image.height, image.size, argv[2]);
    fc_image_result_free(&image);
    return 0;
}
