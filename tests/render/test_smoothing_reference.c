/* test_smoothing_reference.c — the narrow-range filter and curvature flow
 * (compute shaders whose invocations each filter a run or block of pixels)
 * against plain C implementations of their equations, pixel by pixel, on a
 * depth image with every case in it: a slope whose kernel widths vary from
 * pixel to pixel, particle-sized bumps, an occluder in front, holes of
 * background, and the image's edges. A pixel computed from the wrong
 * neighbours (a run's or a block's edge, a partial workgroup) is off by far
 * more than rounding. */
#include <math.h>

#include "smoothing_fixture.h"
#include "test_util.h"

/* Float rounding (exp, sums of a few dozen depths around 5), far below any
 * neighbour mix-up: neighbouring depths differ by 1e-2 or more here. */
#define TOLERANCE 1e-4f
/* The narrow-range filter's automatic kernel half-width in projected particle
 * radii (NARROW_RANGE_RADII_PER_KERNEL of smoothing.c) and its clamp (mu). */
#define RADII_PER_KERNEL 2.0f
#define CLAMP_RADII 1.0f
#define MAX_KERNEL_RADIUS 64

/* Depth 3 at the left edge to 8 at the right, so kernels span 4 to 9 pixels,
 * with bumps, a disc in front, background holes and scattered background. */
static void scene_reference(float *depth)
{
    uint32_t state = 12345u;
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++) {
            state = state * 1664525u + 1013904223u;
            float noise = (float)(state >> 8) / 16777216.0f - 0.5f;
            float z = 3.0f + 5.0f * x / (SF_W - 1) + 0.02f * sinf(0.9f * x) * cosf(0.7f * y) + 0.01f * noise;
            bool hole = (x - 90) * (x - 90) + (y - 20) * (y - 20) < 64 || (state & 63u) == 0;
            depth[y * SF_W + x] = hole ? 0.0f : z;
        }
    scene_add_disc(depth, 40.0f, 60.0f, 14.0f, 2.5f);
}

static float depth_or_background(const float *depth, int x, int y)
{
    return x >= 0 && y >= 0 && x < SF_W && y < SF_H ? depth[y * SF_W + x] : 0.0f;
}

/* ---- Narrow-range filter, one pass along (ax, ay); channels: filtered, unfiltered ---- */

enum { ACCEPTED, IN_FRONT, BEHIND, OFF_GRID };

static int classify(bool on_grid, float zq, float nearest, float farthest)
{
    if (!on_grid)
        return OFF_GRID;
    if (zq <= 0.0f || zq > farthest)
        return BEHIND;
    return zq < nearest ? IN_FRONT : ACCEPTED;
}

static void extend(float zq, float jump, float *nearest, float *farthest)
{
    *nearest = fminf(*nearest, zq - jump);
    *farthest = fmaxf(*farthest, zq + jump);
}

static void narrow_pixel(const float *z_in, const float *unfiltered_in, int x, int y, int ax, int ay,
                         const fc_smoothing_params *p, float *z_out, float *unfiltered_out)
{
    int i0 = y * SF_W + x;
    float z = z_in[i0], unfiltered = unfiltered_in[i0] > 0.0f ? unfiltered_in[i0] : z;
    *z_out = z;
    *unfiltered_out = unfiltered;
    if (z <= 0.0f)
        return;
    float c = ax ? p->pixel_scale[0] : p->pixel_scale[1];
    int radius = (int)ceilf(RADII_PER_KERNEL * (p->particle_radius / (z * c)));
    radius = radius < 1 ? 1 : radius > MAX_KERNEL_RADIUS ? MAX_KERNEL_RADIUS : radius;
    float sigma = (float)radius / 3.0f, inv_two_sigma2 = 0.5f / (sigma * sigma);
    float clamped = unfiltered + CLAMP_RADII * p->particle_radius, jump = p->depth_jump;
    float fn = z - jump, ff = z + jump, bn = fn, bf = ff;
    float sum = z, weight_sum = 1.0f;
    for (int i = 1; i <= radius; i++) {
        int fx = x + i * ax, fy = y + i * ay, bx = x - i * ax, by = y - i * ay;
        float zf = depth_or_background(z_in, fx, fy), zb = depth_or_background(z_in, bx, by);
        int fwd = classify(fx < SF_W && fy < SF_H, zf, fn, ff);
        int bwd = classify(bx >= 0 && by >= 0, zb, bn, bf);
        if (fwd == ACCEPTED)
            extend(zf, jump, &fn, &ff);
        if (bwd == ACCEPTED)
            extend(zb, jump, &bn, &bf);
        if (fwd == IN_FRONT || bwd == IN_FRONT || fwd == OFF_GRID || bwd == OFF_GRID)
            continue;
        float w = expf(-(float)(i * i) * inv_two_sigma2);
        sum += w * ((fwd == BEHIND ? clamped : zf) + (bwd == BEHIND ? clamped : zb));
        weight_sum += 2.0f * w;
    }
    *z_out = sum / weight_sum;
}

static void narrow_reference(float *z, const fc_smoothing_params *p)
{
    static float unfiltered[SF_PIXELS], z_next[SF_PIXELS], unfiltered_next[SF_PIXELS];
    for (int i = 0; i < SF_PIXELS; i++)
        unfiltered[i] = 0.0f;   /* raw depth: the first pass takes it from the first channel */
    for (uint32_t pass = 0; pass < 2 * p->iterations; pass++) {
        int ax = pass % 2 == 0, ay = !ax;
        for (int y = 0; y < SF_H; y++)
            for (int x = 0; x < SF_W; x++)
                narrow_pixel(z, unfiltered, x, y, ax, ay, p, &z_next[y * SF_W + x], &unfiltered_next[y * SF_W + x]);
        for (int i = 0; i < SF_PIXELS; i++) {
            z[i] = z_next[i];
            unfiltered[i] = unfiltered_next[i];
        }
    }
}

/* ---- Curvature flow: van der Laan et al. 2009, eqs. 1-8, one explicit Euler step ---- */

static float neighbour(const float *z_in, int x, int y, float z, float jump, bool *same)
{
    float d = depth_or_background(z_in, x, y);
    *same = d > 0.0f && fabsf(d - z) <= jump;
    return *same ? d : z;
}

static float curvature_pixel(const float *z_in, int x, int y, const fc_smoothing_params *p)
{
    float z = z_in[y * SF_W + x], jump = p->depth_jump;
    if (z <= 0.0f)
        return z;
    bool ur, ul, dr, dl, unused;
    float zr = neighbour(z_in, x + 1, y, z, jump, &unused), zl = neighbour(z_in, x - 1, y, z, jump, &unused);
    float zu = neighbour(z_in, x, y + 1, z, jump, &unused), zd = neighbour(z_in, x, y - 1, z, jump, &unused);
    float zur = neighbour(z_in, x + 1, y + 1, z, jump, &ur), zul = neighbour(z_in, x - 1, y + 1, z, jump, &ul);
    float zdr = neighbour(z_in, x + 1, y - 1, z, jump, &dr), zdl = neighbour(z_in, x - 1, y - 1, z, jump, &dl);
    float zx = 0.5f * (zr - zl), zy = 0.5f * (zu - zd);
    float zxx = zr - 2.0f * z + zl, zyy = zu - 2.0f * z + zd;
    float zxy = ur && ul && dr && dl ? 0.25f * (zur - zul - zdr + zdl) : 0.0f;
    float cx = p->pixel_scale[0], cy = p->pixel_scale[1];
    float gx = zx / cx, gy = zy / cy;
    float d_hat = gx * gx + gy * gy + z * z;
    float d_hat_x = 2.0f * (gx * zxx / cx + gy * zxy / cy + z * zx);
    float d_hat_y = 2.0f * (gx * zxy / cx + gy * zyy / cy + z * zy);
    float e_x = 0.5f * zx * d_hat_x - zxx * d_hat, e_y = 0.5f * zy * d_hat_y - zyy * d_hat;
    float twice_h = (e_x / cx + e_y / cy) / (d_hat * sqrtf(d_hat));
    float dt = 0.5f * z / (1.0f / cx + 1.0f / cy);
    return z - dt * 0.5f * twice_h;
}

static void curvature_reference(float *z, const fc_smoothing_params *p)
{
    static float next[SF_PIXELS];
    for (uint32_t step = 0; step < p->iterations; step++) {
        for (int y = 0; y < SF_H; y++)
            for (int x = 0; x < SF_W; x++)
                next[y * SF_W + x] = curvature_pixel(z, x, y, p);
        for (int i = 0; i < SF_PIXELS; i++)
            z[i] = next[i];
    }
}

static void check_against_reference(smoothing_fixture *sf, fc_smoothing method, uint32_t iterations)
{
    static float scene[SF_PIXELS], gpu[SF_PIXELS], cpu[SF_PIXELS];
    scene_reference(scene);
    fc_smoothing_params params = smoothing_params(method, iterations, 1.0f);
    CHECK_CODE(smoothing_apply(sf, scene, &params, gpu), FC_OK);
    for (int i = 0; i < SF_PIXELS; i++)
        cpu[i] = scene[i];
    if (method == FC_SMOOTHING_NARROW)
        narrow_reference(cpu, &params);
    else
        curvature_reference(cpu, &params);
    float worst = 0.0f, moved = 0.0f;
    int worst_at = 0;
    for (int i = 0; i < SF_PIXELS; i++) {
        moved = fmaxf(moved, fabsf(cpu[i] - scene[i]));
        if (fabsf(gpu[i] - cpu[i]) > worst) {
            worst = fabsf(gpu[i] - cpu[i]);
            worst_at = i;
        }
    }
    CHECK_MSG(moved > 10.0f * TOLERANCE, "method %d: the reference barely moved the surface (%g)", (int)method,
              moved);
    CHECK_MSG(worst <= TOLERANCE, "method %d, %u iterations: pixel (%d, %d) is %g, the reference says %g",
              (int)method, iterations, worst_at % SF_W, worst_at / SF_W, gpu[worst_at], cpu[worst_at]);
}

int main(void)
{
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    check_against_reference(&sf, FC_SMOOTHING_NARROW, 1);
    check_against_reference(&sf, FC_SMOOTHING_NARROW, 3);
    check_against_reference(&sf, FC_SMOOTHING_CURVATURE, 1);
    check_against_reference(&sf, FC_SMOOTHING_CURVATURE, 10);
    smoothing_close(&sf);
    return test_result();
}
