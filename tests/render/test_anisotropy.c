/* test_anisotropy.c — the anisotropy passes (anisotropy.h) through real GL:
 * on a jittered block of a few hundred particles every ellipsoid (smoothed
 * centre, neighbour count, G and its principal axes) agrees with a C
 * reference in double precision written from Yu & Turk's equations (brute
 * force neighbours, its own Jacobi iterated to convergence); a straight line
 * of particles gives ellipsoids elongated along it at the largest stretch
 * allowed; an isolated particle stays exactly the sphere at its position; and
 * the ellipsoids are computed once per upload, not per render, camera or
 * radius. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "anisotropy.h"
#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define RADIUS 0.01f

/* ---- C reference ------------------------------------------------------- */

typedef struct reference {
    double centre[3];
    double g[3][3];
    double stretch_max;
    double axis[3];          /* the longest axis (unit) */
    double sigma[3];         /* covariance eigenvalues, largest first */
    int neighbours;
    bool borderline;         /* a neighbour within rounding of the support radius: counts may differ */
} reference;

/* Cyclic Jacobi on a symmetric 3x3 matrix until the off-diagonal vanishes:
 * eigenvalues on a's diagonal, eigenvectors in v's columns. */
static void jacobi(double a[3][3], double v[3][3])
{
    memset(v, 0, 9 * sizeof(double));
    for (int k = 0; k < 3; k++)
        v[k][k] = 1.0;
    for (int sweep = 0; sweep < 60; sweep++) {
        double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        if (off < 1e-300)
            return;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                if (a[p][q] == 0.0)
                    continue;
                double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                double t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < 3; k++) {   /* a <- a P */
                    double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {   /* a <- P^T a */
                    double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {   /* v <- v P */
                    double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
}

/* Eigenvalues largest first with their vectors as columns. */
static void sorted_eigen(const double m[3][3], double values[3], double vectors[3][3])
{
    double a[3][3], v[3][3];
    memcpy(a, m, sizeof a);
    jacobi(a, v);
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (a[order[j]][order[j]] > a[order[i]][order[i]]) {
                int t = order[i];
                order[i] = order[j];
                order[j] = t;
            }
    for (int i = 0; i < 3; i++) {
        values[i] = a[order[i]][order[i]];
        for (int k = 0; k < 3; k++)
            vectors[k][i] = v[k][order[i]];
    }
}

/* Yu & Turk 2013 for particle i with anisotropy.h's parameters and the
 * support radius the pipeline found for the frame (its spacing estimate is
 * fc_frame_estimate_radius's, tested on its own). */
static reference reference_ellipsoid(const float *x, int count, int i, double support)
{
    reference r = {0};
    double weight = 0.0, first[3] = {0}, second[3][3] = {{0}};
    for (int j = 0; j < count; j++) {
        double d[3], dist = 0.0;
        for (int k = 0; k < 3; k++) {
            d[k] = (double)x[3 * j + k] - (double)x[3 * i + k];
            dist += d[k] * d[k];
        }
        double q = sqrt(dist) / support;
        r.borderline |= fabs(q - 1.0) < 1e-4;
        if (q >= 1.0)
            continue;
        double w = 1.0 - q * q * q;
        weight += w;
        r.neighbours++;
        for (int k = 0; k < 3; k++) {
            first[k] += w * d[k];
            for (int l = 0; l < 3; l++)
                second[k][l] += w * d[k] * d[l];
        }
    }
    double mean[3], covariance[3][3];
    /* The smoothing fades out below N_eps neighbours (none: the particle's own centre). */
    double lambda = FC_ANISOTROPY_LAMBDA * fmin(1.0, (double)r.neighbours / FC_ANISOTROPY_MIN_NEIGHBOURS);
    for (int k = 0; k < 3; k++) {
        mean[k] = first[k] / weight;
        r.centre[k] = x[3 * i + k] + lambda * mean[k];
    }
    for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++)
            covariance[k][l] = second[k][l] / weight - mean[k] * mean[l];
    double axes[3][3];
    sorted_eigen(covariance, r.sigma, axes);
    double stretch[3] = {1.0, 1.0, 1.0};
    if (r.neighbours >= (int)FC_ANISOTROPY_MIN_NEIGHBOURS && r.sigma[0] > 0.0) {
        double s2 = fmax(r.sigma[1] / r.sigma[0], 1.0 / FC_ANISOTROPY_MAX_RATIO);
        double s3 = fmax(r.sigma[2] / r.sigma[0], 1.0 / FC_ANISOTROPY_MAX_RATIO);
        double g = cbrt(s2 * s3);
        stretch[0] = 1.0 / g;
        stretch[1] = s2 / g;
        stretch[2] = s3 / g;
    }
    r.stretch_max = stretch[0];
    for (int k = 0; k < 3; k++) {
        r.axis[k] = axes[k][0];
        for (int l = 0; l < 3; l++) {
            r.g[k][l] = 0.0;
            for (int m = 0; m < 3; m++)
                r.g[k][l] += axes[k][m] * axes[l][m] / stretch[m];
        }
    }
    return r;
}

/* ---- GPU side ---------------------------------------------------------- */

static void g_of(const fc_ellipsoid *e, double g[3][3])
{
    const float *v = e->inverse;
    double m[3][3] = {{v[0], v[1], v[2]}, {v[1], v[3], v[4]}, {v[2], v[4], v[5]}};
    memcpy(g, m, sizeof m);
}

/* The ellipsoid's longest axis: G's eigenvector of the smallest eigenvalue. */
static void longest_axis(const fc_ellipsoid *e, double axis[3])
{
    double g[3][3], values[3], vectors[3][3];
    g_of(e, g);
    sorted_eigen(g, values, vectors);
    for (int k = 0; k < 3; k++)
        axis[k] = vectors[k][2];
}

/* Renders once with the anisotropic kernel (computing the ellipsoids) and
 * reads them back, with the support radius they had. */
static fc_ellipsoid *ellipsoids_of(render_fixture *f, const float *positions, int count, float radius,
                                   double *support)
{
    fc_camera cam = axis_camera(3.0, 16, 16);
    fc_settings settings = test_settings(radius, FC_SMOOTHING_NONE, 0);
    settings.kernel = FC_KERNEL_ANISOTROPIC;
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, positions, (uint64_t)count, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    fc_image_free(&depth);
    fc_ellipsoid *out = calloc((size_t)count, sizeof *out);
    fc_error err = {0};
    const fc_anisotropy *a = fc_pipeline_anisotropy(f->pipeline);
    CHECK_CODE(fc_anisotropy_read(a, (uint64_t)count, out, &err), FC_OK);
    *support = a->support;
    return out;
}

static uint32_t lcg(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

/* A jittered 8 x 8 x 6 block at spacing 1.82 radii (the daemon's estimate),
 * away from the origin so float positions carry the cancellation the GPU
 * must avoid, plus two isolated particles. */
static int jittered_block(float *x)
{
    const float spacing = 2.0f * RADIUS / 1.1f;
    uint32_t state = 777u;
    int n = 0;
    for (int k = 0; k < 6; k++)
        for (int j = 0; j < 8; j++)
            for (int i = 0; i < 8; i++) {
                int ijk[3] = {i, j, k};
                const float origin[3] = {0.31f, -0.27f, 0.73f};
                for (int c = 0; c < 3; c++) {
                    float jitter = ((float)lcg(&state) / 16777216.0f - 0.5f) * 0.4f * spacing;
                    x[3 * n + c] = origin[c] + (float)ijk[c] * spacing + jitter;
                }
                n++;
            }
    const float isolated[6] = {0.9f, 0.2f, 0.1f, -0.4f, 0.5f, 0.6f};
    memcpy(x + 3 * n, isolated, sizeof isolated);
    return n + 2;
}

static void test_against_reference(render_fixture *f)
{
    float x[3 * 400];
    int count = jittered_block(x);
    double support;
    fc_ellipsoid *gpu = ellipsoids_of(f, x, count, RADIUS, &support);
    /* The jittered lattice's nearest neighbours are somewhat closer than its spacing. */
    const double spacing = 2.0 * RADIUS / 1.1;
    CHECK_MSG(support > 1.6 * spacing && support < 2.3 * spacing, "support %g for spacing %g", support, spacing);
    int compared = 0, ellipsoids = 0, spheres = 0, axes_compared = 0;
    double worst_centre = 0.0, worst_g = 0.0, worst_axis = 1.0;
    for (int i = 0; i < count; i++) {
        reference r = reference_ellipsoid(x, count, i, support);
        if (r.borderline)
            continue;
        compared++;
        CHECK_MSG((int)gpu[i].neighbours == r.neighbours, "particle %d: %g neighbours, reference %d", i,
                  (double)gpu[i].neighbours, r.neighbours);
        for (int k = 0; k < 3; k++)
            worst_centre = fmax(worst_centre, fabs(gpu[i].centre[k] - r.centre[k]));
        double g[3][3];
        g_of(&gpu[i], g);
        for (int k = 0; k < 3; k++)
            for (int l = 0; l < 3; l++)
                worst_g = fmax(worst_g, fabs(g[k][l] - r.g[k][l]));
        CHECK_MSG(fabs(gpu[i].stretch_max - r.stretch_max) < 1e-3 * r.stretch_max,
                  "particle %d: longest stretch %g, reference %g", i, (double)gpu[i].stretch_max, r.stretch_max);
        bool sphere = r.stretch_max == 1.0;
        spheres += sphere;
        ellipsoids += !sphere;
        if (sphere)
            CHECK_MSG(gpu[i].stretch_max == 1.0f, "particle %d: a sphere in the reference", i);
        /* The longest axis is defined where the two largest eigenvalues differ. */
        if (!sphere && r.sigma[0] > 1.2 * r.sigma[1]) {
            double axis[3];
            longest_axis(&gpu[i], axis);
            double dot = fabs(axis[0] * r.axis[0] + axis[1] * r.axis[1] + axis[2] * r.axis[2]);
            worst_axis = fmin(worst_axis, dot);
            axes_compared++;
        }
    }
    printf("reference: %d of %d compared (%d ellipsoids, %d spheres, %d axes); worst centre %.3g, G %.3g, "
           "axis |cos| %.6f\n",
           compared, count, ellipsoids, spheres, axes_compared, worst_centre, worst_g, worst_axis);
    CHECK(compared > count * 9 / 10 && ellipsoids > 100 && spheres >= 2 && axes_compared > 20);
    CHECK_MSG(worst_centre < 2e-6, "smoothed centres off by %g", worst_centre);
    CHECK_MSG(worst_g < 2e-3, "G off by %g", worst_g);
    CHECK_MSG(worst_axis > 0.999, "longest axes differ: |cos| %g", worst_axis);
    /* The isolated particles: exactly the sphere at their position. */
    for (int i = count - 2; i < count; i++) {
        CHECK(gpu[i].stretch_max == 1.0f && gpu[i].neighbours == 1.0f);
        CHECK(memcmp(gpu[i].centre, x + 3 * i, sizeof gpu[i].centre) == 0);
    }
    free(gpu);
}

/* A block at spacing 1 sets the frame's spacing (the support radius: 2.2);
 * far from it, particles 0.21 apart on a line each have up to 21 neighbours,
 * all on the line, so the covariance has rank one and both short axes are
 * clamped at the longest / k_r: stretches k_r^(2/3) along the line,
 * k_r^(-1/3) across. The two ends have 11, below N_eps: spheres. */
static void test_line_elongates(render_fixture *f)
{
    enum { LINE = 41, BLOCK = 512, COUNT = LINE + BLOCK };
    const double dir[3] = {1.0 / sqrt(5.25), 2.0 / sqrt(5.25), 0.5 / sqrt(5.25)};
    float *x = malloc(3 * COUNT * sizeof *x);
    for (int i = 0; i < LINE; i++)
        for (int k = 0; k < 3; k++)
            x[3 * i + k] = (float)(0.1 * k + (i - LINE / 2) * 0.21 * dir[k]);
    for (int i = 0; i < BLOCK; i++) {
        x[3 * (LINE + i)] = 20.0f + (float)(i % 8);
        x[3 * (LINE + i) + 1] = (float)(i / 8 % 8);
        x[3 * (LINE + i) + 2] = (float)(i / 64);
    }
    double support;
    fc_ellipsoid *gpu = ellipsoids_of(f, x, COUNT, 0.55f, &support);
    CHECK_NEAR(support, FC_ANISOTROPY_SUPPORT_SPACINGS, 1e-4);
    CHECK(gpu[0].stretch_max == 1.0f && gpu[LINE - 1].stretch_max == 1.0f);
    for (int i = 1; i < LINE - 1; i++) {
        CHECK_MSG(gpu[i].stretch_max > 2.0f, "particle %d: longest stretch %g", i, (double)gpu[i].stretch_max);
        double axis[3];
        longest_axis(&gpu[i], axis);
        double dot = fabs(axis[0] * dir[0] + axis[1] * dir[1] + axis[2] * dir[2]);
        CHECK_MSG(dot > 0.999, "particle %d: longest axis at |cos| %g to the line", i, dot);
    }
    const fc_ellipsoid *middle = &gpu[LINE / 2];
    CHECK_NEAR(middle->stretch_max, FC_ANISOTROPY_MAX_STRETCH, 1e-3);
    /* G's eigenvalues are the inverse stretches: 1/k_r^(2/3) along, k_r^(1/3) across (twice). */
    double g[3][3], values[3], vectors[3][3];
    g_of(middle, g);
    sorted_eigen(g, values, vectors);
    CHECK_NEAR(values[0], cbrt(FC_ANISOTROPY_MAX_RATIO), 2e-3);
    CHECK_NEAR(values[1], cbrt(FC_ANISOTROPY_MAX_RATIO), 2e-3);
    CHECK_NEAR(values[2], 1.0 / FC_ANISOTROPY_MAX_STRETCH, 2e-3);
    free(gpu);
    free(x);
}

/* The ellipsoids follow the frame, not the camera, the radius or the image. */
static void test_computed_once_per_frame_and_radius(render_fixture *f)
{
    float x[3 * 400];
    int count = jittered_block(x);
    fc_frame frame = {.count = (uint64_t)count, .positions = x};
    fc_error err = {0};
    CHECK_CODE(fc_pipeline_upload(f->pipeline, &frame, NULL, &err), FC_OK);
    const fc_anisotropy *a = fc_pipeline_anisotropy(f->pipeline);
    uint32_t before = a->computations;
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    fc_image img = {0};
    fc_camera cam = axis_camera(3.0, 32, 24);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_DEPTH, 0, &img, NULL, &err), FC_OK);
    CHECK(a->computations == before);   /* spheres need none */
    settings.kernel = FC_KERNEL_ANISOTROPIC;
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_DEPTH, 0, &img, NULL, &err), FC_OK);
    CHECK(a->computations == before + 1);
    fc_camera other = axis_camera(2.0, 40, 30);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &other, &settings, FC_AOV_COLOR, 1, &img, NULL, &err), FC_OK);
    CHECK(a->computations == before + 1);
    settings.radius = 1.5f * RADIUS;
    CHECK_CODE(fc_pipeline_render(f->pipeline, &other, &settings, FC_AOV_DEPTH, 0, &img, NULL, &err), FC_OK);
    CHECK(a->computations == before + 1);
    CHECK_CODE(fc_pipeline_upload(f->pipeline, &frame, NULL, &err), FC_OK);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &other, &settings, FC_AOV_DEPTH, 0, &img, NULL, &err), FC_OK);
    CHECK(a->computations == before + 2);
    fc_image_free(&img);
}

/* 1M particles in tight clusters of 8 (0.1 apart) on a grid of pitch 1:
 * the grid over their bounds is capped at 2 cells per particle (1.7M cells),
 * so the prefix sum runs on three levels (1024 cells per block). Every
 * particle must find exactly its 7 cluster mates (too few to smooth its
 * centre: it stays where it is): a cell counted, scanned or scattered
 * wrongly loses or adds neighbours. */
static void test_large_grid(render_fixture *f)
{
    enum { SIDE = 50, CLUSTERS = SIDE * SIDE * SIDE, COUNT = 8 * CLUSTERS };
    float *x = malloc(3 * (size_t)COUNT * sizeof *x);
    uint32_t state = 31u;
    for (int c = 0; c < CLUSTERS; c++)
        for (int k = 0; k < 8; k++) {
            float *p = x + 3 * (8 * c + k);
            p[0] = (float)(c % SIDE) + 0.1f * (float)(k & 1) + 0.01f * ((float)lcg(&state) / 16777216.0f);
            p[1] = (float)(c / SIDE % SIDE) + 0.1f * (float)(k >> 1 & 1) + 0.01f * ((float)lcg(&state) / 16777216.0f);
            p[2] = (float)(c / SIDE / SIDE) + 0.1f * (float)(k >> 2) + 0.01f * ((float)lcg(&state) / 16777216.0f);
        }
    double support;
    fc_ellipsoid *gpu = ellipsoids_of(f, x, COUNT, 0.05f, &support);
    const fc_anisotropy *a = fc_pipeline_anisotropy(f->pipeline);
    CHECK_MSG(a->cells > 1024u * 1024u, "%u cells: fewer than three scan levels", a->cells);
    int wrong = 0;
    double worst_centre = 0.0;
    for (int i = 0; i < COUNT; i++) {
        wrong += gpu[i].neighbours != 8.0f;
        if (i % 997 == 0) {   /* the reference over the cluster alone: every other particle is out of reach */
            reference r = reference_ellipsoid(x + 3 * (i / 8 * 8), 8, i % 8, support);
            for (int k = 0; k < 3; k++)
                worst_centre = fmax(worst_centre, fabs(gpu[i].centre[k] - r.centre[k]));
        }
    }
    printf("large grid: %u cells, support %g, %d of %d particles with other than 8 neighbours, worst centre %.3g\n",
           a->cells, support, wrong, COUNT, worst_centre);
    CHECK(wrong == 0);
    CHECK_MSG(worst_centre < 1e-5, "smoothed centres off by %g", worst_centre);
    free(gpu);
    free(x);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_against_reference(&f);
    test_line_elongates(&f);
    test_computed_once_per_frame_and_radius(&f);
    test_large_grid(&f);
    fixture_close(&f);
    return test_result();
}
