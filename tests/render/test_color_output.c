/* test_color_output.c — the shaded image: fluid pixels differ from the
 * background where the particles are and are exactly the background
 * elsewhere; rows run top to bottom; the 8-bit image is the sRGB encoding of
 * the float one. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "render_fixture.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 72
#define RADIUS 0.12f
#define CLUSTER_SIDE 4
#define CLUSTER_COUNT (CLUSTER_SIDE * CLUSTER_SIDE * CLUSTER_SIDE)
/* Two particles far outside the view give both frames the same bounds, so the
 * background (floor height, checker size, depth range) is the same too. */
#define OUTRIGGERS 2

/* The cluster: a block of particles centred 1 above the camera target. */
static void make_frames(float *with_fluid, float *without_fluid)
{
    float *p = with_fluid;
    for (int i = 0; i < CLUSTER_SIDE; i++)
        for (int j = 0; j < CLUSTER_SIDE; j++)
            for (int k = 0; k < CLUSTER_SIDE; k++, p += 3) {
                p[0] = (i - 1.5f) * 0.15f;
                p[1] = 1.0f + (j - 1.5f) * 0.15f;
                p[2] = (k - 1.5f) * 0.15f;
            }
    const float outriggers[OUTRIGGERS * 3] = {-100.0f, 0.7f, -0.3f, 100.0f, 1.3f, 0.3f};
    memcpy(p, outriggers, sizeof outriggers);
    memcpy(without_fluid, outriggers, sizeof outriggers);
}

static const uint8_t *rgba_u8(const fc_image *img, uint32_t x, uint32_t row)
{
    return (const uint8_t *)img->pixels + 4 * ((size_t)row * img->width + x);
}

static const float *rgba_f32(const fc_image *img, uint32_t x, uint32_t row)
{
    return (const float *)img->pixels + 4 * ((size_t)row * img->width + x);
}

static int max_channel_difference(const uint8_t *a, const uint8_t *b)
{
    int worst = 0;
    for (int c = 0; c < 4; c++)
        worst = abs(a[c] - b[c]) > worst ? abs(a[c] - b[c]) : worst;
    return worst;
}

/* The filmic curve of environment.frag.glsl (Narkowicz's ACES fit): 8-bit
 * images are the float image (linear HDR radiance) through it. */
static double filmic(double x)
{
    return fmin(fmax(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0), 1.0);
}

static double srgb_encode(double linear)
{
    linear = fmin(fmax(linear, 0.0), 1.0);
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    static float with_fluid[3 * (CLUSTER_COUNT + OUTRIGGERS)], without_fluid[3 * OUTRIGGERS];
    make_frames(with_fluid, without_fluid);
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_CURVATURE, 10);
    const uint64_t count = CLUSTER_COUNT + OUTRIGGERS;

    fc_image color = {0}, linear = {0}, depth = {0}, background = {0};
    CHECK_CODE(render_positions(&f, with_fluid, count, &cam, &settings, FC_AOV_COLOR, 1, &color), FC_OK);
    CHECK_CODE(render_positions(&f, with_fluid, count, &cam, &settings, FC_AOV_COLOR, 0, &linear), FC_OK);
    CHECK_CODE(render_positions(&f, with_fluid, count, &cam, &settings, FC_AOV_SMOOTHED_DEPTH, 0, &depth), FC_OK);
    CHECK_CODE(render_positions(&f, without_fluid, OUTRIGGERS, &cam, &settings, FC_AOV_COLOR, 1, &background),
               FC_OK);
    CHECK(color.type == FC_PIXEL_U8 && color.channels == 4 && color.width == WIDTH && color.height == HEIGHT);
    CHECK(linear.type == FC_PIXEL_F32 && linear.channels == 4);

    int fluid = 0, fluid_distinct = 0, fluid_in_lower_half = 0, background_changed = 0, not_opaque = 0;
    double worst_srgb_error = 0.0;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++) {
            const uint8_t *shaded = rgba_u8(&color, x, row), *behind = rgba_u8(&background, x, row);
            if (pixel_f32(&depth, x, row) > 0.0f) {
                fluid++;
                fluid_distinct += max_channel_difference(shaded, behind) > 4;
                fluid_in_lower_half += row >= HEIGHT / 2;
            } else {
                background_changed += max_channel_difference(shaded, behind) != 0;
            }
            not_opaque += shaded[3] != 255;
            for (int c = 0; c < 3; c++)
                worst_srgb_error = fmax(worst_srgb_error,
                                        fabs(shaded[c] / 255.0 - srgb_encode(filmic(rgba_f32(&linear, x, row)[c]))));
        }
    /* The cluster spans about 0.57 + 2r = 0.81 units, about 20 of the 72 rows. */
    CHECK_MSG(fluid > 150, "%d fluid pixels", fluid);
    CHECK_MSG(fluid_distinct >= 0.95 * fluid, "%d of %d fluid pixels differ from the background", fluid_distinct,
              fluid);
    CHECK_MSG(fluid_in_lower_half == 0, "%d fluid pixels in the lower half: rows are upside down",
              fluid_in_lower_half);
    CHECK_MSG(background_changed == 0, "%d background pixels differ from the render without fluid",
              background_changed);
    CHECK(not_opaque == 0);
    CHECK_MSG(worst_srgb_error <= 1.0 / 255.0, "8-bit output off the filmic curve and sRGB encoding by %g",
              worst_srgb_error);

    fc_image_free(&color);
    fc_image_free(&linear);
    fc_image_free(&depth);
    fc_image_free(&background);
    fixture_close(&f);
    return test_result();
}
