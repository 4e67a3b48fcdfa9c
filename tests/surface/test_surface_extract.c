/* test_surface_extract.c — surface mesh extraction (surface_extract.h)
 * through real GL: a ball of particles gives one closed 2-manifold of Euler
 * characteristic 2, faces and normals pointing out, whose volume and mean
 * radius are within 3% of the field's own isosurface found independently here
 * (the metaball and SPH sums in double, bisected along rays); two blobs give
 * two parts; a thin sheet over many blocks is closed (no cracks between
 * blocks); a speed linear in x comes back linear; two extractions are
 * byte-identical; and hostile input (NaN, huge counts, grids past the
 * budget) gets typed errors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_frame.h"
#include "fc_settings.h"
#include "field_check.h"
#include "mesh_check.h"
#include "render_fixture.h"
#include "surface_extract.h"
#include "surface_mesher.h"
#include "test_util.h"

#define SPACING 1.0f
#define RADIUS 0.55f          /* the splash data's radius per spacing */
#define BALL_RADIUS 5.0f
#define DIRECTIONS 2000

typedef struct points {
    float *xyz;
    uint64_t count, capacity;
} points;

static void add_point(points *p, float x, float y, float z)
{
    if (p->count == p->capacity) {
        p->capacity = p->capacity ? 2 * p->capacity : 1024;
        p->xyz = realloc(p->xyz, p->capacity * 3 * sizeof(float));
    }
    p->xyz[3 * p->count] = x;
    p->xyz[3 * p->count + 1] = y;
    p->xyz[3 * p->count + 2] = z;
    p->count++;
}

/* The lattice points within `radius` of c (a fixed jitter-free lattice: the same run to run). */
static void add_ball(points *p, const float c[3], float radius)
{
    int n = (int)ceilf(radius / SPACING);
    for (int k = -n; k <= n; k++)
        for (int j = -n; j <= n; j++)
            for (int i = -n; i <= n; i++) {
                float x = i * SPACING, y = j * SPACING, z = k * SPACING;
                if (x * x + y * y + z * z <= radius * radius)
                    add_point(p, c[0] + x, c[1] + y, c[2] + z);
            }
}

static fc_frame frame_of(const points *p)
{
    return (fc_frame){.count = p->count, .positions = p->xyz};
}

static fc_settings mesh_settings(fc_surface_kernel kernel, float cell, uint32_t smoothing)
{
    fc_settings s;
    fc_settings_default(&s);
    s.radius = RADIUS;
    s.surface_kernel = kernel;
    s.surface_cell = cell;
    s.surface_smoothing = smoothing;
    return s;
}

/* ---- the field, independently: a metaball or cubic-spline sum in double ---- */

/* A lone particle's field at one radius: its surface is its sphere. */
static double iso_of(fc_surface_kernel kernel, double radius)
{
    return field_check_weight(kernel, radius, radius);
}

static double field_at(const points *p, fc_surface_kernel kernel, double radius, const double x[3])
{
    double f = 0.0;
    for (uint64_t i = 0; i < p->count; i++) {
        double d2 = 0.0;
        for (int a = 0; a < 3; a++) {
            double d = x[a] - p->xyz[3 * i + a];
            d2 += d * d;
        }
        f += field_check_weight(kernel, radius, sqrt(d2));
    }
    return f;
}

/* Along DIRECTIONS rays from the centre (a Fibonacci sphere), the radius where
 * the field falls through the iso value, bisected from outside inwards; the
 * mean of those radii and the volume they enclose (4 pi / 3 x mean r^3). */
static void isosurface_of_ball(const points *p, fc_surface_kernel kernel, double radius, double *mean_radius,
                               double *volume)
{
    double iso = iso_of(kernel, radius), sum = 0.0, sum3 = 0.0;
    for (int k = 0; k < DIRECTIONS; k++) {
        double z = 1.0 - (2.0 * k + 1.0) / DIRECTIONS, rho = sqrt(1.0 - z * z), phi = k * 2.399963229728653;
        double dir[3] = {rho * cos(phi), rho * sin(phi), z};
        double lo = 0.0, hi = BALL_RADIUS + 3.0 * radius;
        for (double r = hi; r > 0.0; r -= 0.05) {   /* the outermost crossing */
            double x[3] = {r * dir[0], r * dir[1], r * dir[2]};
            if (field_at(p, kernel, radius, x) >= iso) {
                lo = r;
                hi = r + 0.05;
                break;
            }
        }
        for (int it = 0; it < 30; it++) {
            double mid = 0.5 * (lo + hi), x[3] = {mid * dir[0], mid * dir[1], mid * dir[2]};
            if (field_at(p, kernel, radius, x) >= iso)
                lo = mid;
            else
                hi = mid;
        }
        double r = 0.5 * (lo + hi);
        sum += r;
        sum3 += r * r * r;
    }
    *mean_radius = sum / DIRECTIONS;
    *volume = 4.0 * M_PI / 3.0 * sum3 / DIRECTIONS;
}

/* ---- tests ---- */

/* radius: the particles'. */
static void check_ball(render_fixture *f, fc_surface_kernel kernel, float radius, float cell, uint32_t smoothing)
{
    points p = {0};
    add_ball(&p, (float[3]){0, 0, 0}, BALL_RADIUS);
    fc_frame frame = frame_of(&p);
    fc_settings s = mesh_settings(kernel, cell, smoothing);
    s.radius = radius;
    fc_surface_mesh m;
    fc_error err;
    fc_code code = fc_surface_extract(f->pipeline, &frame, &s, &m, &err);
    CHECK_MSG(code == FC_OK, "%s", err.message);
    if (code != FC_OK) {
        free(p.xyz);
        return;
    }
    mesh_topology t = mesh_check_topology(&m);
    CHECK_MSG(t.closed_manifold && t.euler == 2 && t.components == 1 && t.unused_vertices == 0,
              "kernel %d cell %.2f: closed %d euler %lld components %u unused %u", kernel, cell,
              t.closed_manifold, (long long)t.euler, t.components, t.unused_vertices);
    double c[3] = {0, 0, 0}, field_r, volume;
    isosurface_of_ball(&p, kernel, s.radius, &field_r, &volume);
    double mesh_v = mesh_volume(&m), mesh_r = mesh_mean_distance(&m, c);
    CHECK_MSG(fabs(mesh_v / volume - 1.0) < 0.03 && fabs(mesh_r / field_r - 1.0) < 0.03,
              "kernel %d cell %.2f smoothing %u: volume %.3f vs %.3f, mean radius %.4f vs %.4f", kernel, cell,
              smoothing, mesh_v, volume, mesh_r, field_r);
    /* Consistently oriented and enclosing a positive volume: every face points out. The lattice's
     * bumps tilt some faces from the radial direction, never most; the field's normals agree with the faces. */
    CHECK_MSG(mesh_v > 0 && mesh_outward_faces(&m, c) > 0.95 && mesh_normals_agree(&m) > 0.99,
              "faces away from the centre %.4f, normals agreeing with the faces %.4f", mesh_outward_faces(&m, c),
              mesh_normals_agree(&m));
    printf("ball kernel %d cell %.2f smoothing %u: %u vertices, %u triangles, volume %.3f (field %.3f), "
           "radius %.4f (field %.4f)\n", kernel, cell, smoothing, m.vertex_count, m.triangle_count, mesh_v, volume,
           mesh_r, field_r);
    fc_surface_mesh_free(&m);
    free(p.xyz);
}

/* The anisotropic kernel (metaballs on the renderer's ellipsoids): a ball is
 * still one closed surface, near the spheres' (its inside particles keep
 * their shape, its surface ones flatten along it). */
static void test_anisotropic_ball(render_fixture *f)
{
    points p = {0};
    add_ball(&p, (float[3]){0, 0, 0}, BALL_RADIUS);
    fc_frame frame = frame_of(&p);
    fc_settings s = mesh_settings(FC_SURFACE_KERNEL_ANISOTROPIC, 1.0f, 4);
    fc_surface_mesh m;
    fc_error err;
    fc_code code = fc_surface_extract(f->pipeline, &frame, &s, &m, &err);
    CHECK_MSG(code == FC_OK, "%s", err.message);
    if (code == FC_OK) {
        mesh_topology t = mesh_check_topology(&m);
        double c[3] = {0, 0, 0}, r = mesh_mean_distance(&m, c);
        CHECK_MSG(t.closed_manifold && t.euler == 2 && t.components == 1 && fabs(r / BALL_RADIUS - 1.0) < 0.1,
                  "anisotropic: closed %d euler %lld components %u mean radius %.3f", t.closed_manifold,
                  (long long)t.euler, t.components, r);
        printf("anisotropic ball: %u vertices, mean radius %.4f\n", m.vertex_count, r);
        fc_surface_mesh_free(&m);
    }
    free(p.xyz);
}

static void test_two_blobs(render_fixture *f)
{
    points p = {0};
    add_ball(&p, (float[3]){-6, 0, 0}, 3.0f);
    add_ball(&p, (float[3]){6, 1, 0}, 3.0f);
    fc_frame frame = frame_of(&p);
    fc_settings s = mesh_settings(FC_SURFACE_KERNEL_METABALL, 1.0f, 4);
    fc_surface_mesh m;
    fc_error err;
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &m, &err), FC_OK);
    mesh_topology t = mesh_check_topology(&m);
    CHECK_MSG(t.closed_manifold && t.components == 2 && t.euler == 4, "closed %d components %u euler %lld",
              t.closed_manifold, t.components, (long long)t.euler);
    fc_surface_mesh_free(&m);
    free(p.xyz);
}

/* Fluid at rest as a solver writes it: a block of 12 x 12 x 8 particles one
 * spacing apart, jittered by up to 0.05 spacings (a fixed sequence), meshed
 * at the solver's radius, half the spacing. The field must fill the space
 * between the particles: one closed surface of genus 0 and nothing inside
 * (a kernel that reaches too short leaves a bubble in every lattice cube,
 * each a component of its own), its triangles those of the block's outside. */
static void test_block_at_rest(render_fixture *f, fc_surface_kernel kernel)
{
    points p = {0};
    uint32_t state = 2026;
    for (int k = 0; k < 8; k++)
        for (int j = 0; j < 12; j++)
            for (int i = 0; i < 12; i++) {
                float jitter[3];
                for (int a = 0; a < 3; a++) {
                    state = state * 1664525u + 1013904223u;
                    jitter[a] = 0.05f * SPACING * ((float)(state >> 8) / 8388608.0f - 1.0f);
                }
                add_point(&p, i * SPACING + jitter[0], j * SPACING + jitter[1], k * SPACING + jitter[2]);
            }
    fc_frame frame = frame_of(&p);
    fc_settings s = mesh_settings(kernel, 0.5f, 0);
    s.radius = 0.5f * SPACING;
    fc_surface_mesh m;
    fc_error err;
    fc_code code = fc_surface_extract(f->pipeline, &frame, &s, &m, &err);
    CHECK_MSG(code == FC_OK, "%s", err.message);
    if (code == FC_OK) {
        mesh_topology t = mesh_check_topology(&m);
        /* The outside: about 2 (12 x 12 + 2 x 12 x 8) square spacings, 16 cells of 0.5 r square each per square
         * spacing; marching cubes cut 1-5 triangles from a crossed cell (about 3.4 here), a sponge many
         * times the outside's cells. */
        double outside_cells = 2.0 * (12 * 12 + 2 * 12 * 8) * 16.0;
        CHECK_MSG(t.closed_manifold && t.components == 1 && t.euler == 2 && m.triangle_count < 6.0 * outside_cells,
                  "block at rest, kernel %d: closed %d components %u euler %lld, %u triangles for %.0f outside "
                  "cells", kernel, t.closed_manifold, t.components, (long long)t.euler, m.triangle_count,
                  outside_cells);
        printf("block at rest, kernel %d: %u vertices, %u triangles, %u components\n", kernel, m.vertex_count,
               m.triangle_count, t.components);
        fc_surface_mesh_free(&m);
    }
    free(p.xyz);
}

/* A sheet two particles thick, 40 spacings square, a speed linear in x:
 * at cell 0.5 radii it spans many blocks of 8 cells in x and y. */
static void test_sheet(render_fixture *f)
{
    points p = {0};
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 40; j++)
            for (int i = 0; i < 40; i++)
                add_point(&p, i * SPACING, j * SPACING, k * SPACING);
    fc_frame frame = frame_of(&p);
    float *velocity = malloc(p.count * 3 * sizeof(float));
    for (uint64_t i = 0; i < p.count; i++) {
        velocity[3 * i] = 0.5f * p.xyz[3 * i] + 1.0f;   /* speed 1 + x / 2 */
        velocity[3 * i + 1] = velocity[3 * i + 2] = 0.0f;
    }
    frame.velocity = velocity;
    fc_settings s = mesh_settings(FC_SURFACE_KERNEL_METABALL, 0.5f, 0);
    s.radius = SPACING;   /* kernels over two spacings: the weighted means of x are smooth */
    fc_surface_mesh m;
    fc_error err;
    fc_code code = fc_surface_extract(f->pipeline, &frame, &s, &m, &err);
    CHECK_MSG(code == FC_OK, "%s", err.message);
    if (code == FC_OK) {
        mesh_topology t = mesh_check_topology(&m);
        CHECK_MSG(t.closed_manifold && t.components == 1 && t.euler == 2, "sheet: closed %d components %u euler %lld",
                  t.closed_manifold, t.components, (long long)t.euler);
        CHECK(m.attributes == (FC_SURFACE_SPEED | FC_SURFACE_VELOCITY) && m.speed && m.velocity && !m.density && !m.id);
        /* Away from the sheet's x ends the speed is the linear field at the vertex. */
        double worst = 0.0;
        uint32_t inner = 0;
        for (uint32_t v = 0; m.speed && v < m.vertex_count; v++) {
            double x = m.positions[3 * v];
            if (x < 4.0 || x > 35.0)
                continue;
            inner++;
            worst = fmax(worst, fabs(m.speed[v] - (1.0 + 0.5 * x)));
        }
        CHECK_MSG(inner > 1000 && worst < 0.025, "%u inner vertices, speed off by up to %.4f (0.5 per spacing)",
                  inner, worst);
        printf("sheet: %u vertices, %u triangles, speed within %.4f of linear\n", m.vertex_count, m.triangle_count,
               worst);
        fc_surface_mesh_free(&m);
    }
    free(velocity);
    free(p.xyz);
}

static bool same_mesh(const fc_surface_mesh *a, const fc_surface_mesh *b)
{
    size_t v = a->vertex_count, t = a->triangle_count;
    return a->vertex_count == b->vertex_count && a->triangle_count == b->triangle_count &&
           a->attributes == b->attributes && !memcmp(a->positions, b->positions, v * 12) &&
           !memcmp(a->normals, b->normals, v * 12) && !memcmp(a->indices, b->indices, t * 12) &&
           !memcmp(a->speed, b->speed, v * 4) && !memcmp(a->density, b->density, v * 4) &&
           !memcmp(a->velocity, b->velocity, v * 12) && !memcmp(a->id, b->id, v * 4);
}

static void test_deterministic(render_fixture *f)
{
    points p = {0};
    add_ball(&p, (float[3]){0.3f, -0.2f, 0.1f}, 4.0f);
    fc_frame frame;
    CHECK_CODE(fc_frame_alloc(&frame, p.count, FC_ATTR_VELOCITY | FC_ATTR_DENSITY | FC_ATTR_IDS, NULL), FC_OK);
    memcpy(frame.positions, p.xyz, p.count * 12);
    for (uint64_t i = 0; i < p.count; i++) {
        for (int a = 0; a < 3; a++)
            frame.velocity[3 * i + a] = sinf((float)(i * 3 + a));
        frame.density[i] = 1000.0f + (float)(i % 17);
        frame.ids[i] = (uint32_t)(7919u * i + 13u);
    }
    fc_settings s = mesh_settings(FC_SURFACE_KERNEL_SPH, 0.75f, 3);
    fc_surface_mesh a, b;
    fc_error err;
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &a, &err), FC_OK);
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &b, &err), FC_OK);
    CHECK(a.attributes == (FC_SURFACE_SPEED | FC_SURFACE_DENSITY | FC_SURFACE_VELOCITY | FC_SURFACE_ID));
    CHECK_MSG(a.vertex_count > 0 && same_mesh(&a, &b), "two extractions differ (%u and %u vertices)",
              a.vertex_count, b.vertex_count);
    /* Every id is one of the particles'; densities lie in theirs. */
    bool ids_ok = true, density_ok = true;
    for (uint32_t v = 0; a.id && v < a.vertex_count; v++) {
        ids_ok = ids_ok && a.id[v] % 7919u == 13u % 7919u && a.id[v] / 7919u < p.count;
        density_ok = density_ok && a.density[v] >= 1000.0f - 1e-3f && a.density[v] <= 1016.0f + 1e-3f;
    }
    CHECK(ids_ok && density_ok);
    fc_surface_mesh_free(&a);
    fc_surface_mesh_free(&b);
    fc_frame_free(&frame);
    free(p.xyz);
}

static void test_hostile(render_fixture *f)
{
    fc_error err;
    fc_surface_mesh m;
    float two[6] = {0, 0, 0, 1, NAN, 0};
    fc_frame frame = {.count = 2, .positions = two};
    fc_settings s = mesh_settings(FC_SURFACE_KERNEL_METABALL, 1.0f, 2);
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &m, &err), FC_ERR_INVALID_VALUE);
    CHECK(m.vertex_count == 0 && !m.positions);
    /* A count no arrays could hold: refused before any particle is read. */
    frame = (fc_frame){.count = (uint64_t)1 << 40, .positions = two};
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &m, &err), FC_ERR_LIMIT);
    /* Two particles a million radii apart: more blocks along x than keys hold. */
    float far[6] = {0, 0, 0, 1e6f, 0, 0};
    frame = (fc_frame){.count = 2, .positions = far};
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &m, &err), FC_ERR_LIMIT);
    printf("far apart: %s\n", err.message);
    /* Droplets 10 spacings apart on a 40^3 lattice: each its own blocks, past the grid's budget. */
    points p = {0};
    for (int k = 0; k < 40; k++)
        for (int j = 0; j < 40; j++)
            for (int i = 0; i < 40; i++)
                add_point(&p, i * 10.0f, j * 10.0f, k * 10.0f);
    frame = frame_of(&p);
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &m, &err), FC_ERR_LIMIT);
    printf("sparse droplets: %s\n", err.message);
    free(p.xyz);
    /* A cell outside its domain is the settings' error. */
    frame = (fc_frame){.count = 1, .positions = two};
    s.surface_cell = 0.1f;
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &m, &err), FC_ERR_INVALID_VALUE);
    /* And the pipeline still extracts afterwards: a lone particle is its sphere. */
    s.surface_cell = 0.5f;
    CHECK_CODE(fc_surface_extract(f->pipeline, &frame, &s, &m, &err), FC_OK);
    mesh_topology t = mesh_check_topology(&m);
    CHECK(t.closed_manifold && t.euler == 2);
    double c[3] = {0, 0, 0};
    CHECK_MSG(fabs(mesh_mean_distance(&m, c) / RADIUS - 1.0) < 0.03, "lone particle: radius %.4f",
              mesh_mean_distance(&m, c));
    fc_surface_mesh_free(&m);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    check_ball(&f, FC_SURFACE_KERNEL_METABALL, RADIUS, 1.0f, 0);
    check_ball(&f, FC_SURFACE_KERNEL_METABALL, RADIUS, 0.5f, 4);
    check_ball(&f, FC_SURFACE_KERNEL_SPH, RADIUS, 0.5f, 4);
    test_anisotropic_ball(&f);
    test_two_blobs(&f);
    test_block_at_rest(&f, FC_SURFACE_KERNEL_METABALL);
    test_block_at_rest(&f, FC_SURFACE_KERNEL_SPH);
    test_sheet(&f);
    test_deterministic(&f);
    test_hostile(&f);
    fixture_close(&f);
    return test_result();
}
