/* test_ellipsoid_splat.c — the surface splat of anisotropic ellipsoids
 * (anisotropy.h, ellipsoid_ray.glsl) through real GL: an isolated particle is
 * bit for bit today's sphere in depth and thickness; every pixel of a
 * jittered block of ellipsoids has the nearest depth a C ray cast of the
 * ellipsoids read back from the GPU gives, silhouettes included; long
 * needles' thickness is the sum of their chords (at full resolution; at half,
 * the same footprint); and a
 * jittered two-layer sheet of particles 0.55 spacings in radius, rendered
 * raw (no smoothing), is at least 3x smoother with ellipsoids than with
 * spheres and has no pinhole. Run with "fragment" and "compute", once per
 * surface splat (depth_pass.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "anisotropy.h"
#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

/* Pixels whose ray passes this close to a silhouette (relative to r²) may
 * round either way, as in test_sphere_depth.c. */
#define EDGE_SLACK 0.02
#define DEPTH_TOLERANCE 2e-4

static uint32_t lcg(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

static float jitter(uint32_t *state, float amplitude)
{
    return ((float)lcg(state) / 16777216.0f - 0.5f) * 2.0f * amplitude;
}

static void render(render_fixture *f, const float *x, int count, const fc_camera *cam, float radius, fc_kernel kernel,
                   fc_aov aov, fc_image *out)
{
    fc_settings settings = test_settings(radius, FC_SMOOTHING_NONE, 0);
    settings.kernel = kernel;
    CHECK_CODE(render_positions(f, x, (uint64_t)count, cam, &settings, aov, 0, out), FC_OK);
    CHECK(fixture_splat_as_forced(f));
}

static bool same_image(const fc_image *a, const fc_image *b)
{
    size_t bytes = (size_t)a->width * a->height * a->channels * sizeof(float);
    return a->width == b->width && a->height == b->height && memcmp(a->pixels, b->pixels, bytes) == 0;
}

/* Largest difference between two images of the same size. */
static double largest_difference(const fc_image *a, const fc_image *b)
{
    double worst = 0.0;
    for (size_t i = 0; i < (size_t)a->width * a->height * a->channels; i++)
        worst = fmax(worst, fabs(((const float *)a->pixels)[i] - ((const float *)b->pixels)[i]));
    return worst;
}

/* A particle without neighbours keeps the sphere: the same pixels, the
 * same bits, in depth and (fragment splat) thickness, also off axis. The
 * compute splat sums thickness in fixed point per longest chord, which is
 * longer for ellipsoids: there the thickness agrees to a step (2 x 0.5 x
 * 2.52 / 2^24 for two particles). */
static void test_isolated_particle_is_the_sphere(render_fixture *f)
{
    /* One particle per frame, on and off axis: no neighbour at all. */
    const float x[2][3] = {{0.0f, 0.0f, 0.0f}, {1.4f, 0.9f, -0.5f}};
    fc_camera cam = axis_camera(5.0, 129, 97);
    const fc_aov aovs[2] = {FC_AOV_DEPTH, FC_AOV_THICKNESS};
    for (int p = 0; p < 2; p++)
        for (int i = 0; i < 2; i++) {
            fc_image sphere = {0}, ellipsoid = {0};
            render(f, x[p], 1, &cam, 0.5f, FC_KERNEL_SPHERE, aovs[i], &sphere);
            bool compute = fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_COMPUTE;
            render(f, x[p], 1, &cam, 0.5f, FC_KERNEL_ANISOTROPIC, aovs[i], &ellipsoid);
            /* Unforced, the splat is chosen by sprite size: either may have drawn either. */
            compute = compute || fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_COMPUTE;
            if (i == 0 || !compute)
                CHECK_MSG(same_image(&sphere, &ellipsoid), "isolated particle %d: %s differs from the sphere's", p,
                          i == 0 ? "depth" : "thickness");
            else
                CHECK_MSG(largest_difference(&sphere, &ellipsoid) < 1e-6, "thickness off by %g",
                          largest_difference(&sphere, &ellipsoid));
            double edge;
            const double centre[3] = {0.0, 0.0, 0.0};
            if (p == 0 && i == 0)
                CHECK_NEAR(pixel_f32(&ellipsoid, 64, 48), analytic_sphere_depth(&cam, centre, 0.5, 64, 48, &edge),
                           1e-4);
            fc_image_free(&sphere);
            fc_image_free(&ellipsoid);
        }
}

/* The ray through pixel (x, row) of an axis_camera image against an
 * ellipsoid read back from the GPU, in double: the front hit's linear depth
 * or 0, and how close to the silhouette (as analytic_sphere_depth). */
static double analytic_ellipsoid_hit(const fc_camera *cam, const fc_ellipsoid *e, double radius, uint32_t x,
                                     uint32_t row, double *edge, double *chord)
{
    double fy = 1.0 / tan(cam->fov_y_deg * PI / 360.0), fx = fy * cam->height / cam->width;
    double d[3] = {((x + 0.5) / cam->width * 2.0 - 1.0) / fx, (1.0 - (row + 0.5) / cam->height * 2.0) / fy, -1.0};
    /* An axis camera's view space is world space shifted by the eye. */
    double c[3] = {e->centre[0], e->centre[1], (double)e->centre[2] - cam->eye[2]};
    const float *g = e->inverse;
    double m[3][3] = {{g[0], g[1], g[2]}, {g[1], g[3], g[4]}, {g[2], g[4], g[5]}};
    double a[3], b[3];
    for (int k = 0; k < 3; k++) {
        a[k] = m[k][0] * d[0] + m[k][1] * d[1] + m[k][2] * d[2];
        b[k] = m[k][0] * c[0] + m[k][1] * c[1] + m[k][2] * c[2];
    }
    double aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    double t = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / aa;
    double miss_sq = 0.0;
    for (int k = 0; k < 3; k++)
        miss_sq += (b[k] - t * a[k]) * (b[k] - t * a[k]);
    double half_sq = radius * radius - miss_sq;
    *edge = half_sq / (radius * radius);
    /* The ray's parameter is linear depth; its length per unit of depth is |d|. */
    *chord = half_sq > 0.0 ? 2.0 * sqrt(half_sq / aa) * sqrt(d[0] * d[0] + d[1] * d[1] + 1.0) : 0.0;
    return half_sq > 0.0 ? t - sqrt(half_sq / aa) : 0.0;
}

static double analytic_ellipsoid_depth(const fc_camera *cam, const fc_ellipsoid *e, double radius, uint32_t x,
                                       uint32_t row, double *edge)
{
    double chord;
    return analytic_ellipsoid_hit(cam, e, radius, x, row, edge, &chord);
}

/* A jittered 8 x 8 x 6 block at spacing 1.82 radii: ellipsoids of every
 * orientation, overlapping. */
static int jittered_block(float *x, float radius)
{
    const float spacing = 2.0f * radius / 1.1f;
    uint32_t state = 99u;
    int n = 0;
    for (int k = 0; k < 6; k++)
        for (int j = 0; j < 8; j++)
            for (int i = 0; i < 8; i++, n++) {
                x[3 * n] = ((float)i - 3.5f) * spacing + jitter(&state, 0.2f * spacing);
                x[3 * n + 1] = ((float)j - 3.5f) * spacing + jitter(&state, 0.2f * spacing);
                x[3 * n + 2] = ((float)k - 2.5f) * spacing + jitter(&state, 0.2f * spacing);
            }
    return n;
}

/* Whether the C ray cast `expected` (width x height, 0 where empty) has
 * fluid within PINHOLE_REACH pixels of (px, row) along +x, -x, +y and -y:
 * an empty pixel there is a pinhole the depth resolve may close
 * (pinhole_fill.glsl), not background. */
#define PINHOLE_REACH 3
static bool enclosed(const double *expected, uint32_t width, uint32_t height, uint32_t px, uint32_t row)
{
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    for (int d = 0; d < 4; d++) {
        bool found = false;
        for (int k = 1; k <= PINHOLE_REACH && !found; k++) {
            int64_t x = (int64_t)px + k * dx[d], y = (int64_t)row + k * dy[d];
            found = x >= 0 && y >= 0 && x < width && y < height && expected[(size_t)y * width + (size_t)x] > 0.0;
        }
        if (!found)
            return false;
    }
    return true;
}

/* Every pixel of a depth render of the particles has the nearest depth of
 * a C ray cast of their ellipsoids, as read back: silhouettes (so the
 * sprites' exact boxes, ellipsoid_bounds.glsl) and depths; only pinholes
 * between them (enclosed) may be filled. At least `min_ellipsoids` of them
 * must be ellipsoids. */
static void check_against_ellipsoids(render_fixture *f, const float *x, int count, float radius,
                                     const fc_camera *cam, int min_ellipsoids, const char *what)
{
    fc_image depth = {0};
    render(f, x, count, cam, radius, FC_KERNEL_ANISOTROPIC, FC_AOV_DEPTH, &depth);
    fc_ellipsoid *e = calloc((size_t)count, sizeof *e);
    fc_error err = {0};
    CHECK_CODE(fc_anisotropy_read(fc_pipeline_anisotropy(f->pipeline), (uint64_t)count, e, &err), FC_OK);
    int ellipsoids = 0;
    for (int i = 0; i < count; i++)
        ellipsoids += e[i].stretch_max > 1.1f;
    double *expected = calloc((size_t)depth.width * depth.height, sizeof *expected);
    bool *ambiguous = calloc((size_t)depth.width * depth.height, sizeof *ambiguous);
    CHECK(e && expected && ambiguous);
    for (uint32_t row = 0; row < depth.height; row++)
        for (uint32_t px = 0; px < depth.width; px++) {
            size_t at = (size_t)row * depth.width + px;
            for (int i = 0; i < count; i++) {
                double edge;
                double t = analytic_ellipsoid_depth(cam, &e[i], radius, px, row, &edge);
                ambiguous[at] |= fabs(edge) < EDGE_SLACK;
                if (t > 0.0 && (expected[at] == 0.0 || t < expected[at]))
                    expected[at] = t;
            }
        }
    int covered = 0, wrong_coverage = 0, wrong_depth = 0, filled = 0;
    double worst = 0.0;
    for (uint32_t row = 0; row < depth.height; row++)
        for (uint32_t px = 0; px < depth.width; px++) {
            size_t at = (size_t)row * depth.width + px;
            if (ambiguous[at])
                continue;
            double want = expected[at], got = pixel_f32(&depth, px, row);
            covered += got > 0.0;
            if (want == 0.0 && got > 0.0 && enclosed(expected, depth.width, depth.height, px, row))
                filled++;
            else if ((want == 0.0) != (got == 0.0))
                wrong_coverage++;
            else if (want > 0.0 && fabs(got - want) > DEPTH_TOLERANCE * want)
                wrong_depth++;
            if (want > 0.0 && got > 0.0)
                worst = fmax(worst, fabs(got - want));
        }
    printf("%s: %d of %d ellipsoids, %d pixels covered (%d pinholes filled), worst depth error %.3g\n", what,
           ellipsoids, count, covered, filled, worst);
    CHECK(ellipsoids >= min_ellipsoids && covered > 1000);
    CHECK_MSG(wrong_coverage == 0, "%d pixels disagree with the ellipsoids' silhouettes", wrong_coverage);
    CHECK_MSG(wrong_depth == 0, "%d pixels off the ellipsoids' depth (worst %g)", wrong_depth, worst);
    CHECK_MSG(filled * 1000 <= covered, "%d pinholes filled among %d pixels", filled, covered);
    free(e);
    free(expected);
    free(ambiguous);
    fc_image_free(&depth);
}

/* A jittered block of ellipsoids of every orientation, overlapping: centred,
 * and shifted to the image's upper right corner, where the projection
 * stretches silhouettes most. */
static void test_block_is_its_ellipsoids(render_fixture *f)
{
    const float radius = 0.01f;
    float x[3 * 384];
    int count = jittered_block(x, radius);
    fc_camera cam = axis_camera(0.6, 200, 160);
    check_against_ellipsoids(f, x, count, radius, &cam, count / 2, "block");
    for (int i = 0; i < count; i++) {
        x[3 * i] += 0.2f;
        x[3 * i + 1] += 0.13f;
    }
    check_against_ellipsoids(f, x, count, radius, &cam, count / 2, "block in the corner");
}

/* `line` particles 0.21 apart along a slanted line through the origin, then
 * a `block` of particles 1 apart far out of view, which sets the frame's
 * spacing. */
static void needles(float *x, int line, int block)
{
    const float dir[3] = {0.95f, 0.25f, 0.2f};
    for (int i = 0; i < line; i++)
        for (int k = 0; k < 3; k++)
            x[3 * i + k] = (float)(i - line / 2) * 0.21f * dir[k];
    for (int i = 0; i < block; i++) {
        x[3 * (line + i)] = 40.0f + (float)(i % 8);
        x[3 * (line + i) + 1] = (float)(i / 8 % 8);
        x[3 * (line + i) + 2] = (float)(i / 64);
    }
}

/* Needles 250 pixels long across the image (a line of particles 0.21
 * spacings apart, the spacing set by a block out of view): sprites as large
 * as points can be, whose exact boxes are a fraction of their bounding
 * spheres'. Too large for the compute splat (depth_pass.h): fragment only. */
static void test_needles_are_their_ellipsoids(render_fixture *f)
{
    if (f->splat == FC_SPLAT_COMPUTE)
        return;
    enum { LINE = 15, BLOCK = 512, COUNT = LINE + BLOCK };
    float *x = malloc(3 * COUNT * sizeof *x);
    needles(x, LINE, BLOCK);
    fc_camera cam = axis_camera(3.0, 240, 200);
    check_against_ellipsoids(f, x, COUNT, 0.55f, &cam, LINE - 2, "needles");
    free(x);
}

/* The needles' thickness: at full resolution (the depth pass's splat) every
 * pixel holds the sum of the C chords through the ellipsoids; splatted at half
 * resolution (the depth pass's thickness splat of the reduced view) and resampled, the
 * image holds the same total and differs from the full one by 0.4% of it
 * (the resampling), where spheres would differ by half. */
static void test_needles_thickness(render_fixture *f)
{
    if (f->splat == FC_SPLAT_COMPUTE)
        return;
    enum { LINE = 15, BLOCK = 512, COUNT = LINE + BLOCK };
    float *x = malloc(3 * COUNT * sizeof *x);
    needles(x, LINE, BLOCK);
    fc_camera cam = axis_camera(3.0, 240, 200);
    fc_settings settings = test_settings(0.55f, FC_SMOOTHING_NONE, 0);
    settings.kernel = FC_KERNEL_ANISOTROPIC;
    fc_image full = {0}, half = {0};
    CHECK_CODE(render_positions(f, x, COUNT, &cam, &settings, FC_AOV_THICKNESS, 0, &full), FC_OK);
    settings.thickness_scale = 0.5f;
    CHECK_CODE(render_positions(f, x, COUNT, &cam, &settings, FC_AOV_THICKNESS, 0, &half), FC_OK);
    fc_ellipsoid *e = calloc(COUNT, sizeof *e);
    fc_error err = {0};
    CHECK_CODE(fc_anisotropy_read(fc_pipeline_anisotropy(f->pipeline), COUNT, e, &err), FC_OK);
    int wrong = 0;
    double worst = 0.0;
    for (uint32_t row = 0; row < full.height; row++)
        for (uint32_t px = 0; px < full.width; px++) {
            double expected = 0.0, edge, chord;
            bool ambiguous = false;
            for (int i = 0; i < LINE; i++) {
                analytic_ellipsoid_hit(&cam, &e[i], 0.55, px, row, &edge, &chord);
                ambiguous |= fabs(edge) < EDGE_SLACK;
                expected += chord;
            }
            double diff = fabs(pixel_f32(&full, px, row) - expected);
            if (!ambiguous && diff > 1e-4 * (1.0 + expected))
                wrong++;
            if (!ambiguous)
                worst = fmax(worst, diff);
        }
    double full_sum = image_sum(&full), half_sum = image_sum(&half), apart = 0.0;
    for (uint32_t row = 0; row < full.height; row++)
        for (uint32_t px = 0; px < full.width; px++)
            apart += fabs(pixel_f32(&half, px, row) - pixel_f32(&full, px, row));
    fc_image spheres = {0};
    settings.kernel = FC_KERNEL_SPHERE;
    CHECK_CODE(render_positions(f, x, COUNT, &cam, &settings, FC_AOV_THICKNESS, 0, &spheres), FC_OK);
    double sphere_apart = 0.0;
    for (uint32_t row = 0; row < full.height; row++)
        for (uint32_t px = 0; px < full.width; px++)
            sphere_apart += fabs(pixel_f32(&spheres, px, row) - pixel_f32(&full, px, row));
    fc_image_free(&spheres);
    printf("needles' thickness: worst %.3g against the C chords; total %.4g at full, %.4g at half resolution, "
           "apart %.3g (spheres at half: %.3g)\n",
           worst, full_sum, half_sum, apart / full_sum, sphere_apart / full_sum);
    CHECK_MSG(wrong == 0, "%d pixels off the ellipsoids' chords (worst %g)", wrong, worst);
    CHECK_MSG(fabs(half_sum - full_sum) < 0.02 * full_sum, "half-resolution thickness total %g, full %g", half_sum,
              full_sum);
    /* Spheres hold the same total (the same volume): the footprint tells the shapes apart. */
    CHECK_MSG(apart < 0.05 * full_sum && sphere_apart > 0.3 * full_sum,
              "half resolution %g apart from full, spheres %g", apart / full_sum, sphere_apart / full_sum);
    free(e);
    free(x);
    fc_image_free(&full);
    fc_image_free(&half);
}

/* Two jittered layers of 24 x 24 particles facing the camera, the second
 * offset by half a spacing in x and y and 0.7 spacings behind. */
static int two_layer_sheet(float *x, float spacing)
{
    uint32_t state = 4242u;
    int n = 0;
    for (int layer = 0; layer < 2; layer++)
        for (int j = 0; j < 24; j++)
            for (int i = 0; i < 24; i++, n++) {
                float shift = 0.5f * (float)layer;
                x[3 * n] = ((float)i - 11.5f + shift) * spacing + jitter(&state, 0.15f * spacing);
                x[3 * n + 1] = ((float)j - 11.5f + shift) * spacing + jitter(&state, 0.15f * spacing);
                x[3 * n + 2] = -0.7f * spacing * (float)layer + jitter(&state, 0.15f * spacing);
            }
    return n;
}

typedef struct flatness {
    double rms;      /* of the depth about the least-squares plane */
    int pixels;      /* in the interior */
    int pinholes;    /* interior pixels without fluid */
} flatness;

/* Least-squares plane depth = p0 + p1 x + p2 row over the pixels inside
 * [lo, hi]² in pixel coordinates, by the normal equations. */
static flatness measure_flatness(const fc_image *depth, double lo, double hi)
{
    double m[3][3] = {{0}}, v[3] = {0};
    flatness out = {0};
    for (uint32_t row = 0; row < depth->height; row++)
        for (uint32_t x = 0; x < depth->width; x++) {
            if (x + 0.5 < lo || x + 0.5 > hi || row + 0.5 < lo || row + 0.5 > hi)
                continue;
            double z = pixel_f32(depth, x, row);
            out.pixels++;
            if (z == 0.0) {
                out.pinholes++;
                continue;
            }
            double basis[3] = {1.0, (double)x, (double)row};
            for (int k = 0; k < 3; k++) {
                v[k] += basis[k] * z;
                for (int l = 0; l < 3; l++)
                    m[k][l] += basis[k] * basis[l];
            }
        }
    /* Cramer's rule on the 3x3 normal equations. */
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    double p[3];
    for (int c = 0; c < 3; c++) {
        double mc[3][3];
        memcpy(mc, m, sizeof mc);
        for (int r = 0; r < 3; r++)
            mc[r][c] = v[r];
        p[c] = (mc[0][0] * (mc[1][1] * mc[2][2] - mc[1][2] * mc[2][1]) -
                mc[0][1] * (mc[1][0] * mc[2][2] - mc[1][2] * mc[2][0]) +
                mc[0][2] * (mc[1][0] * mc[2][1] - mc[1][1] * mc[2][0])) /
               det;
    }
    double sum = 0.0;
    int n = 0;
    for (uint32_t row = 0; row < depth->height; row++)
        for (uint32_t x = 0; x < depth->width; x++) {
            double z = pixel_f32(depth, x, row);
            if (x + 0.5 < lo || x + 0.5 > hi || row + 0.5 < lo || row + 0.5 > hi || z == 0.0)
                continue;
            double r = z - (p[0] + p[1] * x + p[2] * row);
            sum += r * r;
            n++;
        }
    out.rms = n > 0 ? sqrt(sum / n) : 0.0;
    return out;
}

static void test_sheet_is_smooth_and_closed(render_fixture *f)
{
    const float spacing = 0.02f, radius = 0.55f * spacing;
    float x[3 * 1152];
    int count = two_layer_sheet(x, spacing);
    const uint32_t size = 256;
    fc_camera cam = axis_camera(0.8, size, size);
    /* The interior: three spacings in from the sheet's edges. */
    const double corner[3] = {-(11.5 - 3.0) * spacing, (11.5 - 3.0) * spacing, 0.0};
    double lo, unused;
    analytic_project(&cam, corner, &lo, &unused);
    double hi = size - lo;
    fc_image sphere = {0}, ellipsoid = {0};
    render(f, x, count, &cam, radius, FC_KERNEL_SPHERE, FC_AOV_DEPTH, &sphere);
    render(f, x, count, &cam, radius, FC_KERNEL_ANISOTROPIC, FC_AOV_DEPTH, &ellipsoid);
    flatness s = measure_flatness(&sphere, lo, hi), e = measure_flatness(&ellipsoid, lo, hi);
    printf("sheet: raw depth RMS about the plane %.3g (spheres) -> %.3g (ellipsoids), %.1fx; interior %d px, "
           "pinholes %d -> %d\n",
           s.rms, e.rms, s.rms / e.rms, e.pixels, s.pinholes, e.pinholes);
    CHECK(e.pixels > 10000);
    CHECK_MSG(s.rms >= 3.0 * e.rms, "roughness %g -> %g: less than 3x smoother", s.rms, e.rms);
    CHECK_MSG(e.pinholes == 0, "%d pinholes in the ellipsoids' sheet", e.pinholes);
    /* The spheres leave gaps between them (18 here), which the depth resolve
     * closes (pinhole_fill.glsl). */
    CHECK_MSG(s.pinholes == 0, "%d pinholes in the spheres' sheet", s.pinholes);
    fc_image_free(&sphere);
    fc_image_free(&ellipsoid);
}

/* Closing pinholes must not close a real gap: two jittered sheets side by
 * side, three spacings apart (1.9 spacings between the spheres' edges),
 * keep every pixel of the gap's middle column empty, whatever the kernel. */
static void test_gap_between_sheets_stays_open(render_fixture *f)
{
    const float spacing = 0.02f, radius = 0.55f * spacing;
    float x[3 * 1152];
    int all = two_layer_sheet(x, spacing), count = 0;
    for (int i = 0; i < all; i++) {
        float *p = &x[3 * i];
        if (fabsf(p[0]) < 1.4f * spacing)
            continue;   /* the gap: |x| < 1.4 spacings */
        memmove(&x[3 * count], p, 3 * sizeof(float));
        count++;
    }
    const uint32_t size = 256;
    fc_camera cam = axis_camera(0.8, size, size);
    const fc_kernel kernels[2] = {FC_KERNEL_SPHERE, FC_KERNEL_ANISOTROPIC};
    for (int k = 0; k < 2; k++) {
        fc_image depth = {0};
        render(f, x, count, &cam, radius, kernels[k], FC_AOV_DEPTH, &depth);
        int filled = 0, rows = 0;
        for (uint32_t row = size / 4; row < 3 * size / 4; row++, rows++)
            filled += pixel_f32(&depth, size / 2, row) != 0.0f;
        CHECK_MSG(filled == 0, "kernel %d: %d of %d gap pixels filled", k, filled, rows);
        fc_image_free(&depth);
    }
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    test_isolated_particle_is_the_sphere(&f);
    test_block_is_its_ellipsoids(&f);
    test_needles_are_their_ellipsoids(&f);
    test_needles_thickness(&f);
    test_sheet_is_smooth_and_closed(&f);
    test_gap_between_sheets_stays_open(&f);
    fixture_close(&f);
    return test_result();
}
