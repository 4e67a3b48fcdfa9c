/* test_smoothing_reference.c — the narrow-range, bilateral and binomial
 * filters and curvature flow (the compute shaders' invocations each filter a
 * run or block of pixels) against plain C implementations of their
 * equations, pixel by pixel, on a depth image with every case in it: a slope whose kernel widths vary from
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
/* The narrow-range and bilateral filters' automatic kernel half-width in
 * projected particle radii (*_RADII_PER_KERNEL of smoothing.c), and the
 * narrow-range clamp (mu). */
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

static int auto_kernel_radius(float z, float c, float particle_radius)
{
    int radius = (int)ceilf(RADII_PER_KERNEL * (particle_radius / (z * c)));
    return radius < 1 ? 1 : radius > MAX_KERNEL_RADIUS ? MAX_KERNEL_RADIUS : radius;
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
    int radius = p->filter_radius > 0 ? (p->filter_radius < MAX_KERNEL_RADIUS ? (int)p->filter_radius
                                                                               : MAX_KERNEL_RADIUS)
                                      : auto_kernel_radius(z, ax ? p->pixel_scale[0] : p->pixel_scale[1],
                                                           p->particle_radius);
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

/* ---- Bilateral filter (Janisz 2012, eqs. 4.1-4.3, about the plane of the local slope), one pass ---- */

/* Depths further than the depth jump from the last accepted one end a side;
 * background is skipped. Returns whether zi is on the centre's surface. */
static bool walk_accepts(float *last, bool *ended, float zi, float jump)
{
    if (*ended || zi <= 0.0f)
        return false;
    if (*last > 0.0f && fabsf(zi - *last) > jump) {
        *ended = true;
        return false;
    }
    *last = zi;
    return true;
}

/* Mean depth and mean distance, Gaussian-weighted, of one side's samples on the surface. */
static bool side_means(const float *z_in, int x, int y, int dx, int dy, int radius, float inv_two_space,
                       float jump, float *depth, float *offset)
{
    float last = z_in[y * SF_W + x], weight = 0.0f, depth_sum = 0.0f, offset_sum = 0.0f;
    bool ended = false;
    for (int i = 1; i <= radius; i++) {
        float zi = depth_or_background(z_in, x + i * dx, y + i * dy);
        if (!walk_accepts(&last, &ended, zi, jump))
            continue;
        float g = expf(-(float)(i * i) * inv_two_space);
        weight += g;
        depth_sum += g * zi;
        offset_sum += g * (float)i;
    }
    *depth = weight > 0.0f ? depth_sum / weight : 0.0f;
    *offset = weight > 0.0f ? offset_sum / weight : 0.0f;
    return weight > 0.0f;
}

static float bilateral_pixel(const float *z_in, int x, int y, int ax, int ay, const fc_smoothing_params *p)
{
    float z = z_in[y * SF_W + x], jump = p->depth_jump;
    if (z <= 0.0f)
        return z;
    int radius = p->filter_radius > 0 ? (p->filter_radius < MAX_KERNEL_RADIUS ? (int)p->filter_radius
                                                                               : MAX_KERNEL_RADIUS)
                                      : auto_kernel_radius(z, ax ? p->pixel_scale[0] : p->pixel_scale[1],
                                                           p->particle_radius);
    float sigma_space = (float)radius / 3.0f, inv_two_space = 0.5f / (sigma_space * sigma_space);
    float inv_two_range = 0.5f / (p->particle_radius * p->particle_radius);
    float fd, fo, bd, bo;
    bool has_f = side_means(z_in, x, y, ax, ay, radius, inv_two_space, jump, &fd, &fo);
    bool has_b = side_means(z_in, x, y, -ax, -ay, radius, inv_two_space, jump, &bd, &bo);
    float slope = has_f && has_b ? (fd - bd) / (fo + bo) : has_f ? (fd - z) / fo : has_b ? (z - bd) / bo : 0.0f;
    float off_plane_sum = 0.0f, weight_sum = 1.0f;
    for (int direction = -1; direction <= 1; direction += 2) {
        float last = z;
        bool ended = false;
        for (int i = 1; i <= radius; i++) {
            float zi = depth_or_background(z_in, x + direction * i * ax, y + direction * i * ay);
            if (!walk_accepts(&last, &ended, zi, jump))
                continue;
            float off_plane = zi - (z + slope * (float)(direction * i));
            float w = expf(-(float)(i * i) * inv_two_space - off_plane * off_plane * inv_two_range);
            off_plane_sum += w * off_plane;
            weight_sum += w;
        }
    }
    return z + off_plane_sum / weight_sum;
}

static void bilateral_reference(float *z, const fc_smoothing_params *p)
{
    static float next[SF_PIXELS];
    for (uint32_t pass = 0; pass < 2 * p->iterations; pass++) {
        int ax = pass % 2 == 0, ay = !ax;
        for (int y = 0; y < SF_H; y++)
            for (int x = 0; x < SF_W; x++)
                next[y * SF_W + x] = bilateral_pixel(z, x, y, ax, ay, p);
        for (int i = 0; i < SF_PIXELS; i++)
            z[i] = next[i];
    }
}

/* ---- Binomial filter with silhouette map (Cords & Staadt §2.2, §3), kernel half-width p->filter_radius ---- */

/* A texel: depth, coverage (smoothing) or map (silhouette), held fluid before. */
typedef struct binomial_texel {
    float depth, weight, original;
} binomial_texel;

#define MAP_EPSILON (1.0f / 256.0f)
/* Wider than the automatic kernel (2 px here), so runs and image edges matter. */
#define BINOMIAL_RADIUS 5

/* C(2R, R + i) / 4^R: the normalized binomial kernel. */
static float binomial_weight(int radius, int i)
{
    double c = 1.0;
    for (int k = 0; k < radius - i; k++)
        c *= (double)(2 * radius - k) / (double)(k + 1);
    return (float)ldexp(c, -2 * radius);   /* divided by 4^R */
}

/* Coverage-weighted sums over one side's samples on the centre's surface. */
static void binomial_side(const binomial_texel *in, int x, int y, int dx, int dy, int radius, float jump,
                          float *weighted_depth, float *coverage, float *first_depth)
{
    float last = in[y * SF_W + x].depth;
    bool ended = false;
    *weighted_depth = *coverage = *first_depth = 0.0f;
    for (int i = 1; i <= radius; i++) {
        int qx = x + i * dx, qy = y + i * dy;
        if (qx < 0 || qy < 0 || qx >= SF_W || qy >= SF_H)
            break;
        binomial_texel t = in[qy * SF_W + qx];
        if (!walk_accepts(&last, &ended, t.depth, jump))
            continue;
        *first_depth = *first_depth > 0.0f ? *first_depth : t.depth;
        *weighted_depth += binomial_weight(radius, i) * t.weight * t.depth;
        *coverage += binomial_weight(radius, i) * t.weight;
    }
}

static binomial_texel binomial_smooth_pixel(const binomial_texel *in, int x, int y, int ax, int ay, int radius,
                                            float jump)
{
    binomial_texel c = in[y * SF_W + x];
    float fw, fc, ff, bw, bc, bf;
    binomial_side(in, x, y, ax, ay, radius, jump, &fw, &fc, &ff);
    binomial_side(in, x, y, -ax, -ay, radius, jump, &bw, &bc, &bf);
    if (c.depth <= 0.0f && fc > 0.0f && bc > 0.0f && fabsf(ff - bf) > jump) {
        /* A background pixel between two surfaces shows the nearer one. */
        if (ff < bf)
            bw = bc = 0.0f;
        else
            fw = fc = 0.0f;
    }
    float coverage = binomial_weight(radius, 0) * c.weight + fc + bc;
    if (coverage <= 0.0f)
        return (binomial_texel){0.0f, 0.0f, 0.0f};
    float weighted = binomial_weight(radius, 0) * c.weight * c.depth + fw + bw;
    return (binomial_texel){weighted / coverage, coverage, c.original};
}

static binomial_texel binomial_map_pixel(const binomial_texel *in, int x, int y, int ax, int ay, int radius,
                                         bool finish)
{
    binomial_texel c = in[y * SF_W + x];
    float map = 0.0f;
    for (int i = -radius; i <= radius; i++) {
        int qx = x + i * ax, qy = y + i * ay;   /* the edge texel repeats off the grid */
        qx = qx < 0 ? 0 : qx >= SF_W ? SF_W - 1 : qx;
        qy = qy < 0 ? 0 : qy >= SF_H ? SF_H - 1 : qy;
        map += binomial_weight(radius, i < 0 ? -i : i) * in[qy * SF_W + qx].weight;
    }
    bool cut = finish && map < 1.0f - MAP_EPSILON && c.original <= 0.0f;
    return (binomial_texel){cut ? 0.0f : c.depth, map, c.original};
}

static void binomial_reference(float *z, const fc_smoothing_params *p)
{
    static binomial_texel t[SF_PIXELS], next[SF_PIXELS];
    int radius = (int)p->filter_radius, passes = 2 * (int)p->iterations;
    for (int i = 0; i < SF_PIXELS; i++) {
        float fluid = z[i] > 0.0f ? 1.0f : 0.0f;
        t[i] = (binomial_texel){z[i], fluid, fluid};
    }
    for (int pass = 0; pass < 2 * passes; pass++) {
        int ax = pass % 2 == 0, ay = !ax;
        bool silhouette = pass >= passes;
        if (pass == passes)   /* the map starts as the binary "has fluid" image of the coverage */
            for (int i = 0; i < SF_PIXELS; i++)
                t[i].weight = t[i].weight > MAP_EPSILON ? 1.0f : 0.0f;
        for (int y = 0; y < SF_H; y++)
            for (int x = 0; x < SF_W; x++)
                next[y * SF_W + x] = silhouette ? binomial_map_pixel(t, x, y, ax, ay, radius, pass + 1 == 2 * passes)
                                                : binomial_smooth_pixel(t, x, y, ax, ay, radius, p->depth_jump);
        for (int i = 0; i < SF_PIXELS; i++)
            t[i] = next[i];
    }
    for (int i = 0; i < SF_PIXELS; i++)
        z[i] = t[i].depth;
}

/* `filter_radius` 0: the kernel from each pixel's depth (the binomial filter's one kernel from the scene's). */
static void check_against_reference(smoothing_fixture *sf, fc_smoothing method, uint32_t iterations,
                                    uint32_t filter_radius)
{
    static float scene[SF_PIXELS], gpu[SF_PIXELS], cpu[SF_PIXELS];
    scene_reference(scene);
    fc_smoothing_params params = smoothing_params(method, iterations, 1.0f);
    params.filter_radius = filter_radius;
    CHECK_CODE(smoothing_apply(sf, scene, &params, gpu), FC_OK);
    for (int i = 0; i < SF_PIXELS; i++)
        cpu[i] = scene[i];
    if (method == FC_SMOOTHING_NARROW)
        narrow_reference(cpu, &params);
    else if (method == FC_SMOOTHING_BILATERAL)
        bilateral_reference(cpu, &params);
    else if (method == FC_SMOOTHING_BINOMIAL)
        binomial_reference(cpu, &params);
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
    CHECK_MSG(worst <= TOLERANCE,
              "method %d, %u iterations, filter radius %u: pixel (%d, %d) is %g, the reference says %g", (int)method,
              iterations, filter_radius, worst_at % SF_W, worst_at / SF_W, gpu[worst_at], cpu[worst_at]);
}

int main(void)
{
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    check_against_reference(&sf, FC_SMOOTHING_NARROW, 1, 0);
    check_against_reference(&sf, FC_SMOOTHING_NARROW, 3, 0);
    /* A fixed kernel: the filter's FC_FIXED_KERNEL program (one weight per tap for a whole run). */
    check_against_reference(&sf, FC_SMOOTHING_NARROW, 3, 5);
    check_against_reference(&sf, FC_SMOOTHING_NARROW, 2, 1);
    check_against_reference(&sf, FC_SMOOTHING_NARROW, 1, 12);
    check_against_reference(&sf, FC_SMOOTHING_BILATERAL, 1, 0);
    check_against_reference(&sf, FC_SMOOTHING_BILATERAL, 2, 0);
    check_against_reference(&sf, FC_SMOOTHING_BINOMIAL, 1, BINOMIAL_RADIUS);
    check_against_reference(&sf, FC_SMOOTHING_BINOMIAL, 3, BINOMIAL_RADIUS);
    check_against_reference(&sf, FC_SMOOTHING_CURVATURE, 1, 0);
    check_against_reference(&sf, FC_SMOOTHING_CURVATURE, 10, 0);
    smoothing_close(&sf);
    return test_result();
}
