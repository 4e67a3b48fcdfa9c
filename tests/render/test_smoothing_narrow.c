/* test_smoothing_narrow.c — what sets the narrow-range filter (Truong &
 * Yuksel 2018) apart, on synthetic depth through the real passes:
 *   bias correction: a tilted plane next to a surface in front of it stays
 *   exactly planar (the mirror sample of a rejected one is dropped too);
 *   a steep continuous slope is not mistaken for a discontinuity;
 *   clamping: silhouettes bend away from the camera, by at most mu r (one
 *   particle radius), never towards it, and the interior stays put. */
#include <math.h>

#include "smoothing_fixture.h"
#include "test_util.h"

#define TOLERANCE 2e-5f

static float max_deviation_from_ramp(const float *in, const float *out, float ramp_limit)
{
    float worst = 0.0f;
    for (int i = 0; i < SF_PIXELS; i++)
        if (in[i] > ramp_limit)
            worst = fmaxf(worst, fabsf(out[i] - in[i]));
    return worst;
}

/* A plane tilted along x, 0.1 radius deeper per pixel, with a disc well in front of it. */
static void test_bias_correction(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            scene[y * SF_W + x] = 5.0f + 0.01f * x;
    scene_add_disc(scene, 64.0f, 48.0f, 15.0f, 4.0f);
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_NARROW, 3, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    float worst = max_deviation_from_ramp(scene, out, 4.5f);
    CHECK_MSG(worst <= TOLERANCE, "the tilted plane moved by up to %g next to the occluder", worst);
}

/* Depth grows by a whole radius per pixel: across the kernel (6 pixels at
 * this depth) that is more than the range's half-width of four radii, but
 * there is no discontinuity anywhere. */
static void test_steep_slope(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            scene[y * SF_W + x] = 5.0f + SF_RADIUS * y;
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_NARROW, 3, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    float worst = max_deviation_from_ramp(scene, out, 0.0f);
    CHECK_MSG(worst <= 1e-4f, "the steep slope moved by up to %g", worst);
}

/* A flat disc on background: its rim recedes by (0, r], its interior stays. */
static void test_silhouette_clamping(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    static uint8_t distance[SF_PIXELS];
    scene_plane(scene, 0.0f);
    scene_add_disc(scene, 64.0f, 48.0f, 30.0f, 5.0f);
    silhouette_distance(scene, distance);
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_NARROW, 1, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    float deepest = 0.0f, nearest = 0.0f, interior = 0.0f;
    int background_changed = 0;
    for (int i = 0; i < SF_PIXELS; i++) {
        if (scene[i] == 0.0f) {
            background_changed += out[i] != 0.0f;
            continue;
        }
        float moved = out[i] - scene[i];
        deepest = fmaxf(deepest, moved);
        nearest = fminf(nearest, moved);
        /* Beyond the reach of an x and a y pass of a 6-pixel kernel nothing changes. */
        if (distance[i] > 8)
            interior = fmaxf(interior, fabsf(moved));
    }
    CHECK_MSG(background_changed == 0, "%d background pixels changed", background_changed);
    CHECK_MSG(deepest > 0.3f * SF_RADIUS && deepest <= SF_RADIUS + TOLERANCE,
              "the rim receded by up to %g, expected (0.3, 1] radius = %g", deepest, SF_RADIUS);
    CHECK_MSG(nearest >= -TOLERANCE, "a pixel came towards the camera by %g", -nearest);
    CHECK_MSG(interior <= TOLERANCE, "the interior moved by %g", interior);
}

int main(void)
{
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    test_bias_correction(&sf);
    test_steep_slope(&sf);
    test_silhouette_clamping(&sf);
    smoothing_close(&sf);
    return test_result();
}
