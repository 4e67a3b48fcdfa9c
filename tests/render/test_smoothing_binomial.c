/* test_smoothing_binomial.c — what sets the Instant Liquids filter (Cords &
 * Staadt) apart, on synthetic depth through the real passes:
 *   one kernel size k for the image, the projected particle radius at the
 *   fluid's typical depth unless set;
 *   the silhouette map closes the outline: a slit narrower than the kernel
 *   fills with the surface around it, while a straight edge and a convex disc
 *   keep exactly their pixels (no skirt of smoothed depth around them). */
#include <math.h>

#include "smoothing_fixture.h"
#include "test_util.h"

#define TOLERANCE 2e-5f

static void check_kernel_radius(const fc_smoothing_params *params, uint32_t expected)
{
    uint32_t radius = fc_binomial_kernel_radius(params);
    CHECK_MSG(radius == expected, "reference depth %g, filter radius %u: kernel radius %u, expected %u",
              (double)params->reference_depth, params->filter_radius, radius, expected);
}

static void test_kernel_size(void)
{
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_BINOMIAL, 1, 1.0f);
    /* r / (z C) = 0.1 / (5 * 2 / (96 * cot 20°)) = 2.64 pixels, rounded up. */
    check_kernel_radius(&params, 3);
    params.reference_depth = 10.0f;   /* 1.32 pixels */
    check_kernel_radius(&params, 2);
    params.reference_depth = 1000.0f;   /* far below a pixel: still a kernel */
    check_kernel_radius(&params, 1);
    params.filter_radius = 7;
    check_kernel_radius(&params, 7);
}

/* Pixels whose fluid status differs between the two images. */
static int outline_changes(const float *a, const float *b)
{
    int changes = 0;
    for (int i = 0; i < SF_PIXELS; i++)
        changes += (a[i] > 0.0f) != (b[i] > 0.0f);
    return changes;
}

static float max_depth_change(const float *in, const float *out)
{
    float worst = 0.0f;
    for (int i = 0; i < SF_PIXELS; i++)
        if (in[i] > 0.0f && out[i] > 0.0f)
            worst = fmaxf(worst, fabsf(out[i] - in[i]));
    return worst;
}

/* A disc with a slit one pixel wide cut from its edge towards the centre. */
static void test_slit_closes(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    scene_plane(scene, 0.0f);
    scene_add_disc(scene, 64.0f, 48.0f, 30.0f, 5.0f);
    for (int y = 48; y < 78; y++)
        scene[y * SF_W + 64] = 0.0f;
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_BINOMIAL, 1, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    int open = 0;
    float worst = 0.0f;
    for (int y = 48; y < 75; y++) {
        float z = out[y * SF_W + 64];
        open += z == 0.0f;
        worst = fmaxf(worst, fabsf(z - 5.0f));
    }
    CHECK_MSG(open == 0 && worst <= TOLERANCE, "%d slit pixels still open, filled ones off by %g", open, worst);
}

/* Fluid left of x = 64 (the image's edges cut it elsewhere). */
static void test_straight_edge_stays(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            scene[y * SF_W + x] = x < 64 ? 5.0f : 0.0f;
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_BINOMIAL, 4, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    CHECK_MSG(outline_changes(scene, out) == 0, "%d pixels changed sides", outline_changes(scene, out));
    CHECK_MSG(max_depth_change(scene, out) <= TOLERANCE, "depth moved by %g", max_depth_change(scene, out));
}

static void test_convex_disc_stays(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    scene_plane(scene, 0.0f);
    scene_add_disc(scene, 64.0f, 48.0f, 25.0f, 5.0f);
    fc_smoothing_params params = smoothing_params(FC_SMOOTHING_BINOMIAL, 4, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    CHECK_MSG(outline_changes(scene, out) == 0, "%d pixels changed sides", outline_changes(scene, out));
    CHECK_MSG(max_depth_change(scene, out) <= TOLERANCE, "depth moved by %g", max_depth_change(scene, out));
}

int main(void)
{
    test_kernel_size();
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    test_slit_closes(&sf);
    test_straight_edge_stays(&sf);
    test_convex_disc_stays(&sf);
    smoothing_close(&sf);
    return test_result();
}
