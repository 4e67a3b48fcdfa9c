/* test_curvature_flow.c — the curvature flow pass on synthetic depth images
 * uploaded as textures (a bump flattens, monotonically; a camera-facing plane,
 * the background and separate surfaces stay put; noise decays without
 * blowing up), and the full pipeline smoothing a dense particle sheet. */
#include <math.h>
#include <stdlib.h>

#include "curvature_flow.h"
#include "render_fixture.h"
#include "test_util.h"

#define W 96
#define H 96
#define PLANE_DEPTH 5.0f
#define DEPTH_JUMP 0.5f

/* Pixel scale of a 40 degree vertical fov over H pixels (2 / (H · cot 20°)). */
static const float PIXEL_SCALE[2] = {2.0f / (W * 2.7474774f), 2.0f / (H * 2.7474774f)};

typedef struct flow_fixture {
    fc_curvature_flow flow;
    fc_render_target input;
} flow_fixture;

static bool flow_open(flow_fixture *ff)
{
    fc_error err = {0};
    ff->input = fc_render_target_init(GL_R32F, false, false);
    if (fc_curvature_flow_create(NULL, &ff->flow, &err) != FC_OK ||
        fc_render_target_resize(&ff->input, W, H, &err) != FC_OK) {
        fprintf(stderr, "curvature flow set-up: %s\n", err.message);
        return false;
    }
    return true;
}

static void flow_close(flow_fixture *ff)
{
    fc_curvature_flow_destroy(&ff->flow);
    fc_render_target_release(&ff->input);
}

/* Runs the pass on `depth` (W x H, GL row order: y = 0 at the bottom) and
 * returns the result in the same order in `out`. */
static fc_code run_flow(flow_fixture *ff, const float *depth, uint32_t iterations, float depth_jump, float *out)
{
    fc_error err = {0};
    glTextureSubImage2D(ff->input.color, 0, 0, 0, W, H, GL_RED, GL_FLOAT, depth);
    const fc_render_target *result = NULL;
    fc_image img = {0};
    fc_code code = fc_curvature_flow_run(&ff->flow, &ff->input, iterations, PIXEL_SCALE, depth_jump, &result, &err);
    if (code == FC_OK)
        code = read_target(result, 1, &img, &err);
    if (code == FC_OK) {
        /* The readback is top to bottom; put it back in GL order. */
        const float *rows = img.pixels;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                out[y * W + x] = rows[(H - 1 - y) * W + x];
    } else {
        fprintf(stderr, "curvature flow: %s\n", err.message);
    }
    fc_image_free(&img);
    return code;
}

/* A camera-facing plane with a Gaussian bump towards the camera in the middle. */
static void make_bump(float *depth, float amplitude, float sigma_px)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float dx = x - W / 2.0f, dy = y - H / 2.0f;
            depth[y * W + x] = PLANE_DEPTH - amplitude * expf(-(dx * dx + dy * dy) / (2.0f * sigma_px * sigma_px));
        }
}

/* How far the nearest fluid pixel stands out of the plane towards the camera. */
static float peak_height(const float *depth)
{
    float nearest = PLANE_DEPTH;
    for (int i = 0; i < W * H; i++)
        if (depth[i] > 0.0f)
            nearest = fminf(nearest, depth[i]);
    return PLANE_DEPTH - nearest;
}

/* Largest |discrete Laplacian| over the interior: how sharply the surface bends. */
static float max_curvature(const float *depth)
{
    float worst = 0.0f;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            const float *p = depth + y * W + x;
            worst = fmaxf(worst, fabsf(p[1] + p[-1] + p[W] + p[-W] - 4.0f * p[0]));
        }
    return worst;
}

static float max_change(const float *a, const float *b)
{
    float worst = 0.0f;
    for (int i = 0; i < W * H; i++)
        worst = fmaxf(worst, fabsf(a[i] - b[i]));
    return worst;
}

static void test_bump_flattens(flow_fixture *ff)
{
    static float bump[W * H], out[W * H];
    make_bump(bump, 0.05f, 4.0f);
    const uint32_t steps[] = {1, 5, 10, 20, 40, 80};
    float height = peak_height(bump), curvature = max_curvature(bump);
    for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++) {
        CHECK_CODE(run_flow(ff, bump, steps[i], DEPTH_JUMP, out), FC_OK);
        float h = peak_height(out), c = max_curvature(out);
        CHECK_MSG(h < height, "%u iterations: peak %g, was %g", steps[i], h, height);
        CHECK_MSG(c < curvature, "%u iterations: curvature %g, was %g", steps[i], c, curvature);
        height = h;
        curvature = c;
    }
    /* 80 steps of about Laplacian/8 spread a 4 pixel bump over roughly 6 pixels. */
    CHECK_MSG(height < 0.5f * peak_height(bump), "peak after 80 iterations %g", height);
    /* Far from the bump the plane has not moved. */
    CHECK_NEAR(out[2 * W + 2], PLANE_DEPTH, 1e-6);
}

static void test_plane_stays(flow_fixture *ff)
{
    static float plane[W * H], out[W * H];
    for (int i = 0; i < W * H; i++)
        plane[i] = PLANE_DEPTH;
    CHECK_CODE(run_flow(ff, plane, 50, DEPTH_JUMP, out), FC_OK);
    CHECK_MSG(max_change(plane, out) <= 1e-6f * PLANE_DEPTH, "plane moved by %g", max_change(plane, out));
}

/* A round patch of fluid with a bump, background around it. */
static void test_background_untouched(flow_fixture *ff)
{
    static float patch[W * H], out[W * H];
    make_bump(patch, 0.05f, 4.0f);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float dx = x - W / 2.0f, dy = y - H / 2.0f;
            if (dx * dx + dy * dy > 30.0f * 30.0f)
                patch[y * W + x] = 0.0f;
        }
    CHECK_CODE(run_flow(ff, patch, 50, DEPTH_JUMP, out), FC_OK);
    int changed_background = 0, lost_fluid = 0;
    for (int i = 0; i < W * H; i++) {
        changed_background += patch[i] == 0.0f && out[i] != 0.0f;
        lost_fluid += patch[i] > 0.0f && !(out[i] > 0.0f);
    }
    CHECK_MSG(changed_background == 0, "%d background pixels changed", changed_background);
    CHECK_MSG(lost_fluid == 0, "%d fluid pixels lost", lost_fluid);
    CHECK(peak_height(out) < peak_height(patch));
}

/* Left half near, right half farther by more than the threshold: the two
 * surfaces must stay apart. The step is shallow enough (about C·z per pixel)
 * that the flow does blend it under a larger threshold, which shows the check
 * would notice. */
static void test_separate_surfaces(flow_fixture *ff)
{
    const float near = PLANE_DEPTH, far = PLANE_DEPTH + 0.05f;
    static float steps[W * H], out[W * H];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            steps[y * W + x] = x < W / 2 ? near : far;
    const int far_edge = (H / 2) * W + W / 2, near_edge = far_edge - 1;
    CHECK_CODE(run_flow(ff, steps, 50, 0.02f, out), FC_OK);
    CHECK_MSG(max_change(steps, out) == 0.0f, "surfaces blended by %g", max_change(steps, out));
    CHECK(out[far_edge] == far);
    CHECK(out[near_edge] == near);

    CHECK_CODE(run_flow(ff, steps, 50, 0.5f, out), FC_OK);
    CHECK_MSG(far - out[far_edge] > 0.005f, "connected far edge moved only to %g", out[far_edge]);
    CHECK_MSG(out[near_edge] - near > 0.005f, "connected near edge moved only to %g", out[near_edge]);
}

/* The time step is stable by construction: pixel noise decays at every
 * iteration count instead of oscillating or blowing up. */
static void test_noise_decays(flow_fixture *ff)
{
    static float noisy[W * H], out[W * H];
    uint32_t state = 12345u;
    for (int i = 0; i < W * H; i++) {
        state = state * 1664525u + 1013904223u;   /* deterministic LCG */
        noisy[i] = PLANE_DEPTH + 0.02f * ((float)(state >> 8) / 16777216.0f - 0.5f);
    }
    float previous = 0.01f;
    const uint32_t counts[] = {1, 3, 10, 30, 100};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        CHECK_CODE(run_flow(ff, noisy, counts[i], DEPTH_JUMP, out), FC_OK);
        float deviation = 0.0f;
        for (int y = 1; y < H - 1; y++)
            for (int x = 1; x < W - 1; x++)
                deviation = fmaxf(deviation, fabsf(out[y * W + x] - PLANE_DEPTH));
        CHECK_MSG(isfinite(deviation) && deviation < previous, "%u iterations: deviation %g, before %g",
                  counts[i], deviation, previous);
        previous = deviation;
    }
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

/* A square sheet of overlapping spheres facing the camera: the raw depth is
 * bumpy with spheres, the smoothed depth must be much smoother. */
static void test_particle_sheet(render_fixture *f)
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
    fc_settings smooth_settings = test_settings(radius, FC_SMOOTHING_CURVATURE, 60);
    fc_image raw = {0}, smooth = {0};
    CHECK_CODE(render_positions(f, positions, SIDE * SIDE, &cam, &raw_settings, FC_AOV_DEPTH, 0, &raw), FC_OK);
    CHECK_CODE(render_positions(f, positions, SIDE * SIDE, &cam, &smooth_settings, FC_AOV_SMOOTHED_DEPTH, 0,
                                &smooth),
               FC_OK);
    double raw_roughness = roughness(&raw, 4.0f * radius), smooth_roughness = roughness(&smooth, 4.0f * radius);
    CHECK_MSG(raw_roughness > 0.0 && smooth_roughness < 0.3 * raw_roughness, "roughness raw %g, smoothed %g",
              raw_roughness, smooth_roughness);
    fc_image_free(&raw);
    fc_image_free(&smooth);
}

int main(void)
{
    render_fixture f;
    flow_fixture ff;
    if (!fixture_open(&f) || !flow_open(&ff))
        return 1;
    test_bump_flattens(&ff);
    test_plane_stays(&ff);
    test_background_untouched(&ff);
    test_separate_surfaces(&ff);
    test_noise_decays(&ff);
    test_particle_sheet(&f);
    flow_close(&ff);
    fixture_close(&f);
    return test_result();
}
