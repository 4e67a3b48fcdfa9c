/* test_shading_color_by.c — colour by attribute (issue 14) through the real
 * pipeline: with absorption high enough that the fluid's colour dominates and
 * reflection, highlight and refraction off, the linear (float) image at the
 * middle of a cluster of one speed is the colormap's colour at that speed;
 * two clusters show the colours of their speeds in order, after the blur
 * and at half-resolution thickness too; --range clamps a speed above it to
 * the top colour; density colours like speed; a frame without the attribute
 * is refused with INVALID_VALUE naming it; color_by none renders the same
 * bytes as before any coloured render, whatever the colormap and range say,
 * and allocates nothing for colour. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "fc_colormap.h"
#include "shading_fixture.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 72
#define RADIUS 0.12f
#define SIDE 4
#define CLUSTER (SIDE * SIDE * SIDE)
#define COUNT (2 * CLUSTER)
#define SPACING 0.15f
#define CLUSTER_X 0.6
/* 8-bit precision, in linear float: what "the same colour" means. */
#define COLOR_TOLERANCE 0.01f

/* Two blocks of particles, left (x = -0.6) and right (x = +0.6), with
 * velocities along x of speed `left` and `right` and densities of the same values. */
static void make_clusters(float *positions, float *velocity, float *density, float left, float right)
{
    for (int n = 0; n < COUNT; n++) {
        int block = n / CLUSTER, i = n % CLUSTER;
        float *p = positions + 3 * n;
        p[0] = (float)(block ? CLUSTER_X : -CLUSTER_X) + ((float)(i % SIDE) - 1.5f) * SPACING;
        p[1] = ((float)(i / SIDE % SIDE) - 1.5f) * SPACING;
        p[2] = ((float)(i / (SIDE * SIDE)) - 1.5f) * SPACING;
        float speed = block ? right : left;
        velocity[3 * n] = 0.0f;
        velocity[3 * n + 1] = -speed * 0.6f;   /* |(0, -0.6, 0.8)| = 1 */
        velocity[3 * n + 2] = speed * 0.8f;
        density[n] = speed;
    }
}

/* Absorption so high that a particle's thickness shows the fluid's colour
 * alone; no Fresnel reflection (ior 1), highlight, refraction or shadow. */
static fc_settings color_settings(fc_color_by by, fc_colormap map, float lo, float hi)
{
    fc_settings s = test_settings(RADIUS, FC_SMOOTHING_CURVATURE, 10);
    for (int c = 0; c < 3; c++)
        s.absorption[c] = 1000.0f;
    s.ior = 1.0f;
    s.specular = 0.0f;
    s.refraction = 0.0f;
    s.thickness_blur = 2;
    s.color_by = by;
    s.colormap = map;
    s.color_range[0] = lo;
    s.color_range[1] = hi;
    return s;
}

/* The pixel where the middle of the block at x projects. */
static void cluster_pixel(const fc_camera *cam, double x, uint32_t *px, uint32_t *row)
{
    const double centre[3] = {x, 0.0, 0.0};
    double fx, frow;
    analytic_project(cam, centre, &fx, &frow);
    *px = (uint32_t)fx;
    *row = (uint32_t)frow;
}

/* The image at the block's middle is the map's colour at t. */
static bool shows_color(const fc_image *img, const fc_camera *cam, double x, fc_colormap map, float t,
                        const char *what)
{
    uint32_t px, row;
    cluster_pixel(cam, x, &px, &row);
    float expected[3];
    fc_colormap_linear(map, t, expected);
    bool ok = true;
    for (uint32_t c = 0; c < 3; c++)
        ok = ok && fabsf(channel_f32(img, px, row, c) - expected[c]) <= COLOR_TOLERANCE;
    CHECK_MSG(ok, "%s: (%.4f %.4f %.4f) at (%u, %u), %s at %.3f is (%.4f %.4f %.4f)", what,
              (double)channel_f32(img, px, row, 0), (double)channel_f32(img, px, row, 1),
              (double)channel_f32(img, px, row, 2), px, row, fc_colormap_name(map), (double)t, (double)expected[0],
              (double)expected[1], (double)expected[2]);
    return ok;
}

static float luminance_at(const fc_image *img, const fc_camera *cam, double x)
{
    uint32_t px, row;
    cluster_pixel(cam, x, &px, &row);
    return 0.2126f * channel_f32(img, px, row, 0) + 0.7152f * channel_f32(img, px, row, 1) +
           0.0722f * channel_f32(img, px, row, 2);
}

static void test_speed_colors(render_fixture *f, const fc_frame *frame, const fc_camera *cam)
{
    /* Speeds 1 and 3 over [0, 4]: a quarter and three quarters up viridis. */
    const float scales[] = {1.0f, 0.5f};
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        fc_settings s = color_settings(FC_COLOR_BY_SPEED, FC_COLORMAP_VIRIDIS, 0.0f, 4.0f);
        s.thickness_scale = scales[i];
        fc_image img = {0};
        CHECK_CODE(render_frame(f, frame, cam, &s, NULL, FC_AOV_COLOR, 0, &img), FC_OK);
        char what[64];
        snprintf(what, sizeof what, "speed 1, thickness scale %g", (double)scales[i]);
        shows_color(&img, cam, -CLUSTER_X, FC_COLORMAP_VIRIDIS, 0.25f, what);
        snprintf(what, sizeof what, "speed 3, thickness scale %g", (double)scales[i]);
        shows_color(&img, cam, CLUSTER_X, FC_COLORMAP_VIRIDIS, 0.75f, what);
        /* Viridis brightens along the map: the faster block is the brighter. */
        CHECK(luminance_at(&img, cam, CLUSTER_X) > luminance_at(&img, cam, -CLUSTER_X) + 0.1f);
        fc_image_free(&img);
    }
}

/* A speed above the range's max takes the top colour, one in it its place. */
static void test_range_clamps(render_fixture *f, const fc_frame *frame, const fc_camera *cam)
{
    fc_settings s = color_settings(FC_COLOR_BY_SPEED, FC_COLORMAP_TURBO, 0.0f, 2.0f);
    fc_image img = {0};
    CHECK_CODE(render_frame(f, frame, cam, &s, NULL, FC_AOV_COLOR, 0, &img), FC_OK);
    shows_color(&img, cam, -CLUSTER_X, FC_COLORMAP_TURBO, 0.5f, "speed 1 of [0, 2]");
    shows_color(&img, cam, CLUSTER_X, FC_COLORMAP_TURBO, 1.0f, "speed 3 above [0, 2]");
    /* And below the min, the bottom colour. */
    s.color_range[0] = 1.5f;
    s.color_range[1] = 2.5f;
    CHECK_CODE(render_frame(f, frame, cam, &s, NULL, FC_AOV_COLOR, 0, &img), FC_OK);
    shows_color(&img, cam, -CLUSTER_X, FC_COLORMAP_TURBO, 0.0f, "speed 1 below [1.5, 2.5]");
    shows_color(&img, cam, CLUSTER_X, FC_COLORMAP_TURBO, 1.0f, "speed 3 above [1.5, 2.5]");
    fc_image_free(&img);
}

static void test_density_colors(render_fixture *f, const fc_frame *frame, const fc_camera *cam)
{
    fc_settings s = color_settings(FC_COLOR_BY_DENSITY, FC_COLORMAP_COOLWARM, 0.0f, 4.0f);
    fc_image img = {0};
    CHECK_CODE(render_frame(f, frame, cam, &s, NULL, FC_AOV_COLOR, 0, &img), FC_OK);
    shows_color(&img, cam, -CLUSTER_X, FC_COLORMAP_COOLWARM, 0.25f, "density 1");
    shows_color(&img, cam, CLUSTER_X, FC_COLORMAP_COOLWARM, 0.75f, "density 3");
    fc_image_free(&img);
}

/* A frame without the attribute: INVALID_VALUE naming what it lacks, for
 * the colour image only. */
static void test_missing_attribute(render_fixture *f, const fc_frame *with, const fc_camera *cam)
{
    fc_frame bare = {.count = with->count, .positions = with->positions};
    fc_error err = {0};
    fc_image img = {0};
    CHECK_CODE(fc_pipeline_upload(f->pipeline, &bare, NULL, &err), FC_OK);
    fc_settings s = color_settings(FC_COLOR_BY_SPEED, FC_COLORMAP_VIRIDIS, 0.0f, 4.0f);
    CHECK_CODE(fc_pipeline_render(f->pipeline, cam, &s, FC_AOV_COLOR, 0, &img, NULL, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "speed") && strstr(err.message, "velocities"), "\"%s\"", err.message);
    s.color_by = FC_COLOR_BY_DENSITY;
    CHECK_CODE(fc_pipeline_render(f->pipeline, cam, &s, FC_AOV_COLOR, 0, &img, NULL, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "density") && strstr(err.message, "densities"), "\"%s\"", err.message);
    CHECK_CODE(fc_pipeline_render(f->pipeline, cam, &s, FC_AOV_DEPTH, 0, &img, NULL, &err), FC_OK);
    fc_image_free(&img);
}

static bool same_image(const fc_image *a, const fc_image *b)
{
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           fc_image_size(a) == fc_image_size(b) && memcmp(a->pixels, b->pixels, fc_image_size(a)) == 0;
}

/* color_by none: the default path, unchanged by the new settings and by a
 * coloured render in between; only a coloured render allocates its targets. */
static void test_none_unchanged(render_fixture *f, const fc_frame *frame, const fc_camera *cam)
{
    fc_settings plain = test_settings(RADIUS, FC_SMOOTHING_CURVATURE, 10);
    plain.thickness_blur = 2;
    fc_image before = {0}, after = {0}, before_f32 = {0}, after_f32 = {0};
    CHECK_CODE(render_frame(f, frame, cam, &plain, NULL, FC_AOV_COLOR, 1, &before), FC_OK);
    CHECK_CODE(render_frame(f, frame, cam, &plain, NULL, FC_AOV_COLOR, 0, &before_f32), FC_OK);
    fc_gpu_memory plain_memory, colored_memory;
    fc_pipeline_gpu_memory(f->pipeline, &plain_memory);

    fc_settings colored = plain;
    colored.color_by = FC_COLOR_BY_SPEED;
    colored.colormap = FC_COLORMAP_MAGMA;
    colored.color_range[0] = 0.5f;
    colored.color_range[1] = 2.0f;
    fc_image img = {0};
    CHECK_CODE(render_frame(f, frame, cam, &colored, NULL, FC_AOV_COLOR, 1, &img), FC_OK);
    CHECK_MSG(!same_image(&img, &before), "colouring by speed changed nothing");
    fc_pipeline_gpu_memory(f->pipeline, &colored_memory);
    CHECK_MSG(colored_memory.render_target_bytes > plain_memory.render_target_bytes,
              "the coloured targets were there before: %llu bytes both",
              (unsigned long long)plain_memory.render_target_bytes);
    CHECK(colored_memory.particle_bytes == plain_memory.particle_bytes + COUNT * sizeof(float));

    fc_settings none_again = colored;
    none_again.color_by = FC_COLOR_BY_NONE;   /* the map and range stay set, unused */
    CHECK_CODE(render_frame(f, frame, cam, &none_again, NULL, FC_AOV_COLOR, 1, &after), FC_OK);
    CHECK_MSG(same_image(&before, &after), "color_by none differs from the render before colouring (8-bit)");
    CHECK_CODE(render_frame(f, frame, cam, &none_again, NULL, FC_AOV_COLOR, 0, &after_f32), FC_OK);
    CHECK_MSG(same_image(&before_f32, &after_f32), "color_by none differs from the render before colouring (float)");
    fc_image_free(&img);
    fc_image_free(&before);
    fc_image_free(&after);
    fc_image_free(&before_f32);
    fc_image_free(&after_f32);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    static float positions[3 * COUNT], velocity[3 * COUNT], density[COUNT];
    make_clusters(positions, velocity, density, 1.0f, 3.0f);
    fc_frame frame = {.count = COUNT, .positions = positions, .velocity = velocity, .density = density};
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);

    /* First, so the plain renders come from a pipeline that never coloured. */
    test_none_unchanged(&f, &frame, &cam);
    test_speed_colors(&f, &frame, &cam);
    test_range_clamps(&f, &frame, &cam);
    test_density_colors(&f, &frame, &cam);
    test_missing_attribute(&f, &frame, &cam);
    fixture_close(&f);
    return test_result();
}
