/* test_smoothing_methods.c — properties every smoothing method must have, run
 * through the real passes on synthetic depth uploaded as a texture:
 *   a camera-facing plane stays where it is;
 *   a bump flattens, its total curvature falling with every added iteration;
 *   two blobs at different depths never blend: the gap between them stays
 *   background, their depths stay theirs (also where one occludes the other);
 *   background away from the fluid stays background;
 * and, through the whole pipeline, a sheet of particles comes out much smoother.
 *
 * usage: test_smoothing_methods curvature|bilateral|binomial|narrow [smooth_scale]
 * At a reduced scale the outline may move by up to one smoothing texel. */
#include <math.h>
#include <stdlib.h>

#include "render_fixture.h"
#include "smoothing_fixture.h"
#include "test_util.h"

#define NEAR_DEPTH 5.0f
#define FAR_DEPTH 6.0f
/* Float rounding of normalized sums of depths around 5. */
#define TOLERANCE 2e-5f
/* The narrow-range filter clamps far neighbours to one radius behind (its mu
 * = 1): its silhouettes may move back by up to that much, never forward. */
#define NARROW_CLAMP SF_RADIUS

typedef struct method_case {
    fc_smoothing method;
    float scale;
    uint32_t block;          /* image pixels per smoothing texel */
    const uint32_t *ladder;  /* increasing iteration counts */
    size_t ladder_length;
    uint32_t separating;     /* iterations for the scenes of separate surfaces */
} method_case;

static const uint32_t CURVATURE_LADDER[] = {1, 5, 10, 20, 40};
static const uint32_t FILTER_LADDER[] = {1, 2, 4, 8};
/* The binomial silhouette map closes gaps up to about the kernel's reach,
 * which grows with the passes; two iterations reach less than half the gap of
 * the blob scene at every scale. */
#define FILTER_SEPARATING 2
#define CURVATURE_SEPARATING 40

static float allowed_recession(const method_case *mc)
{
    return mc->method == FC_SMOOTHING_NARROW ? NARROW_CLAMP : 0.0f;
}

/* Whether `out` is `expected` as a method may leave it: within rounding, or
 * moved back by no more than the method allows. */
static bool keeps_depth(const method_case *mc, float out, float expected)
{
    return out >= expected - TOLERANCE && out <= expected + allowed_recession(mc) + TOLERANCE;
}

static void test_plane_stays(smoothing_fixture *sf, const method_case *mc)
{
    static float plane[SF_PIXELS], out[SF_PIXELS];
    scene_plane(plane, NEAR_DEPTH);
    fc_smoothing_params params = smoothing_params(mc->method, mc->ladder[mc->ladder_length - 1], mc->scale);
    CHECK_CODE(smoothing_apply(sf, plane, &params, out), FC_OK);
    float worst = 0.0f;
    for (int i = 0; i < SF_PIXELS; i++)
        worst = fmaxf(worst, fabsf(out[i] - NEAR_DEPTH));
    CHECK_MSG(worst <= TOLERANCE, "plane moved by %g", worst);
}

static float peak_height(const float *depth)
{
    float nearest = NEAR_DEPTH;
    for (int i = 0; i < SF_PIXELS; i++)
        nearest = fminf(nearest, depth[i]);
    return NEAR_DEPTH - nearest;
}

static void test_bump_flattens(smoothing_fixture *sf, const method_case *mc)
{
    static float bump[SF_PIXELS], out[SF_PIXELS];
    scene_bump(bump, NEAR_DEPTH, 0.05f, 4.0f);
    /* Resampling to a coarser grid and back bends the surface by itself, so
     * at a reduced scale the ladder starts from its first rung. */
    double curvature = mc->block == 1 ? total_curvature(bump, SF_DEPTH_JUMP) : INFINITY;
    float height = mc->block == 1 ? peak_height(bump) : INFINITY;
    for (size_t i = 0; i < mc->ladder_length; i++) {
        fc_smoothing_params params = smoothing_params(mc->method, mc->ladder[i], mc->scale);
        CHECK_CODE(smoothing_apply(sf, bump, &params, out), FC_OK);
        double c = total_curvature(out, SF_DEPTH_JUMP);
        float h = peak_height(out);
        CHECK_MSG(c < curvature, "%u iterations: total curvature %g, before %g", mc->ladder[i], c, curvature);
        CHECK_MSG(h < height, "%u iterations: peak %g, before %g", mc->ladder[i], h, height);
        curvature = c;
        height = h;
    }
    CHECK_MSG(height < 0.75f * peak_height(bump), "peak after %u iterations %g of %g",
              mc->ladder[mc->ladder_length - 1], height, peak_height(bump));
    CHECK_MSG(curvature < total_curvature(bump, SF_DEPTH_JUMP), "total curvature after %u iterations %g of %g",
              mc->ladder[mc->ladder_length - 1], curvature, total_curvature(bump, SF_DEPTH_JUMP));
    /* Far from the bump the plane has not moved. */
    CHECK_NEAR(out[2 * SF_W + 2], NEAR_DEPTH, TOLERANCE);
}

/* Every pixel keeps its kind and its depth, except within one smoothing texel
 * of a silhouette at a reduced scale, where it may turn into background or into
 * the surface next to it, but never into a blend of depths. */
static void check_no_blending(const method_case *mc, const float *in, const float *out, const char *scene)
{
    static uint8_t distance[SF_PIXELS];
    silhouette_distance(in, distance);
    int margin = mc->block == 1 ? 0 : (int)mc->block;
    int changed = 0, blended = 0;
    for (int i = 0; i < SF_PIXELS; i++) {
        bool kept = in[i] > 0.0f ? keeps_depth(mc, out[i], in[i]) : out[i] == 0.0f;
        bool pure = out[i] == 0.0f || keeps_depth(mc, out[i], NEAR_DEPTH) || keeps_depth(mc, out[i], FAR_DEPTH);
        changed += !kept && distance[i] > margin;
        blended += !pure;
    }
    CHECK_MSG(changed == 0, "%s: %d pixels farther than %d from a silhouette changed", scene, changed, margin);
    CHECK_MSG(blended == 0, "%s: %d pixels hold a blend of depths", scene, blended);
}

/* Two discs 20 pixels apart, the right one farther by 2.5 depth jumps. */
static void test_blobs_stay_apart(smoothing_fixture *sf, const method_case *mc)
{
    static float blobs[SF_PIXELS], out[SF_PIXELS];
    scene_plane(blobs, 0.0f);
    scene_add_disc(blobs, 36.0f, 48.0f, 20.0f, NEAR_DEPTH);
    scene_add_disc(blobs, 96.0f, 48.0f, 20.0f, FAR_DEPTH);
    fc_smoothing_params params = smoothing_params(mc->method, mc->separating, mc->scale);
    CHECK_CODE(smoothing_apply(sf, blobs, &params, out), FC_OK);
    check_no_blending(mc, blobs, out, "separate blobs");
    int gap = 0;
    for (int y = 0; y < SF_H; y++)
        for (int x = 56 + (int)mc->block; x < 76 - (int)mc->block; x++)
            gap += out[y * SF_W + x] != 0.0f;
    CHECK_MSG(gap == 0, "%d pixels of the gap between the blobs hold fluid", gap);
}

/* A near disc in front of a far plane that fills the image. */
static void test_occluder_stays_apart(smoothing_fixture *sf, const method_case *mc)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    scene_plane(scene, FAR_DEPTH);
    scene_add_disc(scene, 64.0f, 48.0f, 20.0f, NEAR_DEPTH);
    fc_smoothing_params params = smoothing_params(mc->method, mc->separating, mc->scale);
    CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
    check_no_blending(mc, scene, out, "occluder");
    /* The far surface right next to the near one keeps its depth exactly. */
    int x_beside = 64 + 20 + (int)mc->block;
    CHECK_NEAR(out[48 * SF_W + x_beside], FAR_DEPTH, TOLERANCE);
}

/* Mean |Laplacian| over pixels whose four neighbours show the same surface. */
static double roughness(const fc_image *depth, float jump)
{
    double sum = 0.0;
    int count = 0;
    for (uint32_t row = 1; row + 1 < depth->height; row++)
        for (uint32_t x = 1; x + 1 < depth->width; x++) {
            float c = pixel_f32(depth, x, row);
            float n[4] = {pixel_f32(depth, x + 1, row), pixel_f32(depth, x - 1, row), pixel_f32(depth, x, row + 1),
                          pixel_f32(depth, x, row - 1)};
            bool inside = c > 0.0f;
            for (int i = 0; i < 4; i++)
                inside = inside && n[i] > 0.0f && fabsf(n[i] - c) < jump;
            if (inside) {
                sum += fabs(n[0] + n[1] + n[2] + n[3] - 4.0 * c);
                count++;
            }
        }
    return count ? sum / count : 0.0;
}

/* A square sheet of overlapping spheres facing the camera, through the whole
 * pipeline: the smoothed depth must be much smoother than the raw one. */
static void test_particle_sheet(render_fixture *f, const method_case *mc)
{
    enum { SIDE = 40 };
    static float positions[3 * SIDE * SIDE];
    const float spacing = 0.04f, radius = 0.05f;
    for (int i = 0; i < SIDE; i++)
        for (int j = 0; j < SIDE; j++) {
            float *p = positions + 3 * (i * SIDE + j);
            p[0] = (i - SIDE / 2) * spacing;
            p[1] = (j - SIDE / 2) * spacing;
            p[2] = 0.0f;
        }
    fc_camera cam = axis_camera(3.0, 128, 128);
    fc_settings raw_settings = test_settings(radius, FC_SMOOTHING_NONE, 0);
    fc_settings smooth_settings = test_settings(radius, mc->method, mc->ladder[mc->ladder_length - 1]);
    smooth_settings.smooth_scale = mc->scale;
    fc_image raw = {0}, smooth = {0};
    CHECK_CODE(render_positions(f, positions, SIDE * SIDE, &cam, &raw_settings, FC_AOV_DEPTH, 0, &raw), FC_OK);
    CHECK_CODE(render_positions(f, positions, SIDE * SIDE, &cam, &smooth_settings, FC_AOV_SMOOTHED_DEPTH, 0,
                                &smooth),
               FC_OK);
    CHECK(smooth.width == raw.width && smooth.height == raw.height);
    double raw_roughness = roughness(&raw, 4.0f * radius), smooth_roughness = roughness(&smooth, 4.0f * radius);
    CHECK_MSG(raw_roughness > 0.0 && smooth_roughness < 0.5 * raw_roughness, "roughness raw %g, smoothed %g",
              raw_roughness, smooth_roughness);
    fc_image_free(&raw);
    fc_image_free(&smooth);
}

static bool parse_case(int argc, char **argv, method_case *mc)
{
    int method = argc > 1 ? smoothing_method_by_name(argv[1]) : -1;
    if (method <= FC_SMOOTHING_NONE) {
        fprintf(stderr, "usage: %s curvature|bilateral|binomial|narrow [smooth_scale]\n", argv[0]);
        return false;
    }
    mc->method = (fc_smoothing)method;
    mc->scale = argc > 2 ? strtof(argv[2], NULL) : 1.0f;
    mc->block = fc_resolution_scale_block(mc->scale);
    bool curvature = mc->method == FC_SMOOTHING_CURVATURE;
    mc->ladder = curvature ? CURVATURE_LADDER : FILTER_LADDER;
    mc->ladder_length = curvature ? sizeof CURVATURE_LADDER / sizeof CURVATURE_LADDER[0]
                                  : sizeof FILTER_LADDER / sizeof FILTER_LADDER[0];
    mc->separating = curvature ? CURVATURE_SEPARATING : FILTER_SEPARATING;
    return true;
}

int main(int argc, char **argv)
{
    method_case mc;
    if (!parse_case(argc, argv, &mc))
        return 2;
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    test_plane_stays(&sf, &mc);
    test_bump_flattens(&sf, &mc);
    test_blobs_stay_apart(&sf, &mc);
    test_occluder_stays_apart(&sf, &mc);
    smoothing_close(&sf);

    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_particle_sheet(&f, &mc);
    fixture_close(&f);
    return test_result();
}
