/* test_smoothing_bilateral.c — what sets the bilateral filter (Janisz 2012,
 * §4.1.2.1) apart, on synthetic depth through the real passes:
 *   the range Gaussian: a step of a few particle radii survives much better
 *   than one of a fraction of a radius, and one beyond the depth jump is not
 *   touched at all;
 *   the range is measured from the surface's slope: a bump on a surface seen
 *   at a grazing angle (half a radius deeper per pixel) flattens as well as one
 *   on a surface facing the camera, and a tilted plane stays exactly planar,
 *   also at the image's edges. */
#include <math.h>

#include "smoothing_fixture.h"
#include "test_util.h"

/* Depth steps by `height` from x < 64 to x >= 64; returns how much of the
 * step is left between the two pixels beside it after one pass. */
static float step_kept(smoothing_fixture *sf, float height)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            scene[y * SF_W + x] = x < 64 ? 5.0f : 5.0f + height;
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_BILATERAL, 1, 1.0f);
    if (smoothing_apply(sf, scene, &params, out) != FC_OK)
        return NAN;
    int row = 48 * SF_W;
    return (out[row + 64] - out[row + 63]) / height;
}

static void test_range_weights(smoothing_fixture *sf)
{
    float small = step_kept(sf, 0.2f * SF_RADIUS), large = step_kept(sf, 3.0f * SF_RADIUS);
    float jump = step_kept(sf, 1.5f * SF_DEPTH_JUMP);
    CHECK_MSG(small < 0.5f, "a step of 0.2 radii kept %g of its height", small);
    CHECK_MSG(large > small + 0.2f, "a step of 3 radii kept %g, one of 0.2 radii %g", large, small);
    CHECK_MSG(fabsf(jump - 1.0f) < 1e-5f, "a step beyond the depth jump kept %g", jump);
}

/* The total curvature left of a Gaussian bump on a plane whose depth grows by
 * `slope` per row, after two iterations, relative to the bump's own. */
static double bump_left(smoothing_fixture *sf, float slope)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    scene_bump(scene, 5.0f, 0.05f, 3.0f);
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            scene[y * SF_W + x] += slope * (y - SF_H / 2);
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_BILATERAL, 2, 1.0f);
    if (smoothing_apply(sf, scene, &params, out) != FC_OK)
        return NAN;
    return total_curvature(out, SF_DEPTH_JUMP) / total_curvature(scene, SF_DEPTH_JUMP);
}

static void test_grazing_surface(smoothing_fixture *sf)
{
    double facing = bump_left(sf, 0.0f), grazing = bump_left(sf, 0.5f * SF_RADIUS);
    CHECK_MSG(facing < 0.7, "the bump kept %g of its curvature", facing);
    CHECK_MSG(grazing < 1.2 * facing, "on a surface at a grazing angle the bump kept %g, facing the camera %g",
              grazing, facing);
}

static void test_tilted_plane_stays(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            scene[y * SF_W + x] = 5.0f + 0.02f * (x - SF_W / 2) + 0.05f * (y - SF_H / 2);
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_BILATERAL, 3, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    float worst = 0.0f;
    for (int i = 0; i < SF_PIXELS; i++)
        worst = fmaxf(worst, fabsf(out[i] - scene[i]));
    CHECK_MSG(worst <= 1e-4f, "the tilted plane moved by up to %g", worst);
}

int main(void)
{
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    test_range_weights(&sf);
    test_grazing_surface(&sf);
    test_tilted_plane_stays(&sf);
    smoothing_close(&sf);
    return test_result();
}
