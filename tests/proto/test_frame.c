/* test_frame.c — frame allocation and validation, bounds, settings domains,
 * camera checks and the camera that frames a bounding box. */
#include <stdint.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "test_util.h"

#define PI 3.14159265358979323846

static void test_alloc_follows_attributes(void)
{
    for (uint32_t attributes = 0; attributes <= FC_ATTR_ALL; attributes++) {
        fc_frame f;
        fc_error err;
        CHECK_CODE(fc_frame_alloc(&f, 10, attributes, &err), FC_OK);
        CHECK(f.count == 10 && f.positions != NULL);
        CHECK(fc_frame_attributes(&f) == attributes);
        f.positions[29] = 1.0f; /* the last element exists (ASan would object otherwise) */
        if (f.radius)
            f.radius[9] = 1.0f;
        fc_frame_free(&f);
        CHECK(f.count == 0 && !f.positions && !f.density && !f.velocity && !f.ids && !f.radius);

        /* One block holds the arrays back to back in FRAME's order, the radii last. */
        size_t size = fc_frame_block_size(10, attributes);
        CHECK(size == 10 * fc_frame_particle_bytes(attributes));
        uint8_t block[10 * 36];
        fc_frame_point_into_block(&f, block, 10, attributes);
        CHECK(fc_frame_attributes(&f) == attributes);
        if (attributes & FC_ATTR_RADIUS)
            CHECK((uint8_t *)f.radius == block + size - 40);
    }
    fc_frame zeroed = {0};
    fc_frame_free(&zeroed);
}

static void test_alloc_refusals(void)
{
    fc_frame f;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&f, 0, 0, &err), FC_ERR_USAGE);
    CHECK(f.count == 0 && !f.positions);
    CHECK_CODE(fc_frame_alloc(&f, 1, 1u << 4, &err), FC_ERR_USAGE);
    /* 3 * count floats overflows size_t: refused, never wrapped to a small allocation. */
    CHECK_CODE(fc_frame_alloc(&f, UINT64_MAX / 4, 0, &err), FC_ERR_NOMEM);
    CHECK(f.count == 0 && !f.positions);
}

static void test_validate(void)
{
    fc_frame f;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&f, 3, FC_ATTR_DENSITY | FC_ATTR_VELOCITY | FC_ATTR_IDS, &err), FC_OK);
    memset(f.positions, 0, 9 * sizeof(float));
    memset(f.density, 0, 3 * sizeof(float));
    memset(f.velocity, 0, 9 * sizeof(float));
    memset(f.ids, 0xFF, 3 * sizeof(uint32_t));
    CHECK_CODE(fc_frame_validate(&f, &err), FC_OK);

    f.velocity[7] = NAN;
    CHECK_CODE(fc_frame_validate(&f, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strcmp(err.message, "particle 2 has a non-finite velocity") == 0, "%s", err.message);
    f.density[1] = INFINITY;
    CHECK_CODE(fc_frame_validate(&f, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strcmp(err.message, "particle 1 has a non-finite density") == 0, "%s", err.message);
    f.positions[2] = -INFINITY;
    CHECK_CODE(fc_frame_validate(&f, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strcmp(err.message, "particle 0 has a non-finite position") == 0, "%s", err.message);
    fc_frame_free(&f);

    fc_frame empty = {0};
    CHECK_CODE(fc_frame_validate(&empty, &err), FC_ERR_INVALID_VALUE);
}

/* The median radius: element count/2 of the sorted radii, the frame untouched. */
static void test_median_radius(void)
{
    enum { N = 1001 };
    fc_frame f;
    fc_error err;
    float median = -1;
    CHECK_CODE(fc_frame_alloc(&f, N, 0, &err), FC_OK);
    CHECK_CODE(fc_frame_median_radius(&f, &median, &err), FC_OK);
    CHECK(median == 0.0f); /* no radii */
    fc_frame_free(&f);

    CHECK_CODE(fc_frame_alloc(&f, N, FC_ATTR_RADIUS, &err), FC_OK);
    /* 0.001 .. 1.001 in a scrambled order (i * 389 mod 1001 visits every residue). */
    for (uint32_t i = 0; i < N; i++)
        f.radius[i] = 0.001f * (float)((i * 389u) % N + 1);
    float first = f.radius[0], last = f.radius[N - 1];
    CHECK_CODE(fc_frame_median_radius(&f, &median, &err), FC_OK);
    CHECK_MSG(median == 0.001f * 501, "median %g", (double)median);
    CHECK(f.radius[0] == first && f.radius[N - 1] == last);

    /* Many equal values and an even count: the upper median. */
    f.count = 6;
    const float six[6] = {2, 1, 2, 2, 9, 1};
    memcpy(f.radius, six, sizeof six);
    CHECK_CODE(fc_frame_median_radius(&f, &median, &err), FC_OK);
    CHECK_MSG(median == 2.0f, "median %g", (double)median);
    f.count = 1;
    CHECK_CODE(fc_frame_median_radius(&f, &median, &err), FC_OK);
    CHECK(median == 2.0f);
    f.count = N;
    fc_frame_free(&f);
}

static void test_bounds(void)
{
    float positions[] = {1, -2, 3, -4, 5, 0.5f, 0, 0, 10};
    fc_frame f = {.count = 3, .positions = positions};
    float lo[3], hi[3];
    fc_frame_bounds(&f, lo, hi);
    CHECK(lo[0] == -4 && lo[1] == -2 && lo[2] == 0.5f);
    CHECK(hi[0] == 1 && hi[1] == 5 && hi[2] == 10);
}

static void test_settings_default_and_domains(void)
{
    fc_settings d;
    fc_error err;
    fc_settings_default(&d);
    CHECK(d.radius == 0 && d.smoothing == FC_SMOOTHING_NARROW && d.iterations == 4);
    CHECK(d.fluid_color[0] == 0.02f && d.fluid_color[1] == 0.15f && d.fluid_color[2] == 0.28f);
    CHECK(d.absorption[0] == 0.02f && d.absorption[1] == 0.007f && d.absorption[2] == 0.0035f);
    CHECK(d.ior == 1.33f);
    CHECK_CODE(fc_settings_validate(&d, &err), FC_OK);

    const struct {
        float radius, color, absorption, ior;
        uint32_t iterations, smoothing;
        fc_code expected;
    } cases[] = {
        {0, 0, 0, 1, 0, 0, FC_OK},
        {1e6f, 1, 1e6f, 3, 1000, 1, FC_OK},
        {-1e-6f, 0, 0, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {1.01e6f, 0, 0, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {NAN, 0, 0, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {INFINITY, 0, 0, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {0, 1.001f, 0, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {0, -0.001f, 0, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {0, NAN, 0, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {0, 0, -1, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {0, 0, INFINITY, 1, 0, 0, FC_ERR_INVALID_VALUE},
        {0, 0, 0, 0.999f, 0, 0, FC_ERR_INVALID_VALUE},
        {0, 0, 0, 3.001f, 0, 0, FC_ERR_INVALID_VALUE},
        {0, 0, 0, NAN, 0, 0, FC_ERR_INVALID_VALUE},
        {0, 0, 0, 1, 1001, 0, FC_ERR_INVALID_VALUE},
        {0, 0, 0, 1, 0, FC_SMOOTHING_NARROW + 1, FC_ERR_INVALID_VALUE},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fc_settings s = d;
        s.radius = cases[i].radius;
        s.fluid_color[1] = cases[i].color;
        s.absorption[2] = cases[i].absorption;
        s.ior = cases[i].ior;
        s.iterations = cases[i].iterations;
        s.smoothing = (fc_smoothing)cases[i].smoothing;
        CHECK_MSG(fc_settings_validate(&s, &err) == cases[i].expected, "case %zu: %s", i, err.message);
    }
}

static fc_camera good_camera(void)
{
    return (fc_camera){.eye = {1, 1, 1}, .target = {0, 0, 0}, .up = {0, 0, 1}, .fov_y_deg = 60, .width = 1,
                       .height = 1};
}

static void test_camera_validate(void)
{
    fc_error err;
    fc_camera c = good_camera();
    CHECK_CODE(fc_camera_validate(&c, &err), FC_OK);
    c.fov_y_deg = 179.9f;
    CHECK_CODE(fc_camera_validate(&c, &err), FC_OK);

    fc_camera bad[9];
    for (int i = 0; i < 9; i++)
        bad[i] = good_camera();
    bad[0].eye[0] = NAN;
    bad[1].target[2] = INFINITY;
    bad[2].up[1] = NAN;
    bad[3].eye[0] = bad[3].eye[1] = bad[3].eye[2] = 0;   /* eye == target */
    bad[4].up[0] = bad[4].up[1] = bad[4].up[2] = -3;     /* up parallel to the view direction */
    bad[5].up[2] = 0;                                    /* up zero */
    bad[6].fov_y_deg = 180;
    bad[7].fov_y_deg = -10;
    bad[8].height = 0;
    for (int i = 0; i < 9; i++)
        CHECK_MSG(fc_camera_validate(&bad[i], &err) == FC_ERR_INVALID_VALUE, "case %d", i);
}

/* Projects p with an independent look-at + perspective; returns pixel
 * coordinates (x right, y down) and the view depth. */
static void project(const fc_camera *c, const double p[3], double *px, double *py, double *depth)
{
    double f[3], s[3], u[3], d[3];
    double fl = 0, sl = 0;
    for (int k = 0; k < 3; k++) {
        f[k] = (double)c->target[k] - c->eye[k];
        fl += f[k] * f[k];
    }
    for (int k = 0; k < 3; k++)
        f[k] /= sqrt(fl);
    s[0] = f[1] * c->up[2] - f[2] * c->up[1];
    s[1] = f[2] * c->up[0] - f[0] * c->up[2];
    s[2] = f[0] * c->up[1] - f[1] * c->up[0];
    for (int k = 0; k < 3; k++)
        sl += s[k] * s[k];
    for (int k = 0; k < 3; k++)
        s[k] /= sqrt(sl);
    u[0] = s[1] * f[2] - s[2] * f[1];
    u[1] = s[2] * f[0] - s[0] * f[2];
    u[2] = s[0] * f[1] - s[1] * f[0];
    double x = 0, y = 0, z = 0;
    for (int k = 0; k < 3; k++) {
        d[k] = p[k] - c->eye[k];
        x += d[k] * s[k];
        y += d[k] * u[k];
        z += d[k] * f[k];
    }
    double t = tan(0.5 * c->fov_y_deg * PI / 180.0), aspect = (double)c->width / c->height;
    *px = (x / (z * t * aspect) + 1) * 0.5 * c->width;
    *py = (1 - y / (z * t)) * 0.5 * c->height;
    *depth = z;
}

static void check_framing(uint32_t width, uint32_t height)
{
    float positions[8 * 3];
    const float lo[3] = {1, 2, 3}, hi[3] = {5, 4, 3.5f};
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++)
            positions[3 * i + k] = (i >> k) & 1 ? hi[k] : lo[k];
    fc_frame f = {.count = 8, .positions = positions};
    fc_camera c;
    fc_error err;
    fc_camera_frame_bounds(&f, width, height, &c);
    CHECK_CODE(fc_camera_validate(&c, &err), FC_OK);
    CHECK(c.width == width && c.height == height && c.fov_y_deg == 40.0f);
    CHECK(c.up[0] == 0 && c.up[1] == 0 && c.up[2] == 1);

    /* Looks along (-1, 1.4, -0.9). */
    double view[3], vl = 0, dir_len = sqrt(1 + 1.96 + 0.81);
    for (int k = 0; k < 3; k++) {
        view[k] = (double)c.target[k] - c.eye[k];
        vl += view[k] * view[k];
    }
    vl = sqrt(vl);
    CHECK_NEAR(view[0] / vl, -1 / dir_len, 1e-5);
    CHECK_NEAR(view[1] / vl, 1.4 / dir_len, 1e-5);
    CHECK_NEAR(view[2] / vl, -0.9 / dir_len, 1e-5);

    /* The box centre lands in the image centre. */
    const double centre[3] = {3, 3, 3.25};
    double px, py, depth;
    project(&c, centre, &px, &py, &depth);
    CHECK_NEAR(px, 0.5 * width, 1e-3 * width);
    CHECK_NEAR(py, 0.5 * height, 1e-3 * height);

    /* The bounding sphere exactly touches the narrower field of view. */
    double radius = 0.5 * sqrt(16 + 4 + 0.25);
    double half_y = 20 * PI / 180, half_x = atan(tan(half_y) * width / height);
    CHECK_NEAR(vl, radius / sin(fmin(half_x, half_y)), 1e-4 * vl);

    /* So every corner is in front of the camera and inside the image. */
    for (int i = 0; i < 8; i++) {
        double corner[3] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
        project(&c, corner, &px, &py, &depth);
        CHECK_MSG(depth > 0 && px >= 0 && px <= width && py >= 0 && py <= height,
                  "%ux%u corner %d at (%g, %g) depth %g", width, height, i, px, py, depth);
    }
}

static void test_camera_frames_bounds(void)
{
    check_framing(320, 200);  /* wide: the vertical fov is the narrower */
    check_framing(200, 320);  /* tall: the horizontal fov is */
    check_framing(64, 64);
}

static void test_camera_frames_a_single_point(void)
{
    float p[3] = {1e3f, -2e3f, 5};
    fc_frame f = {.count = 1, .positions = p};
    fc_camera c;
    fc_error err;
    fc_camera_frame_bounds(&f, 16, 9, &c);
    CHECK_CODE(fc_camera_validate(&c, &err), FC_OK);
    CHECK(c.target[0] == p[0] && c.target[1] == p[1] && c.target[2] == p[2]);
}

int main(void)
{
    test_alloc_follows_attributes();
    test_alloc_refusals();
    test_validate();
    test_median_radius();
    test_bounds();
    test_settings_default_and_domains();
    test_camera_validate();
    test_camera_frames_bounds();
    test_camera_frames_a_single_point();
    return test_result();
}
