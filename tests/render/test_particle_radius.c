/* test_particle_radius.c — per-particle radii (FRAME attribute bit 3,
 * PROTOCOL.md 5) through the real pipeline: two spheres of different radii
 * side by side against their analytic depths and silhouettes; a frame whose
 * radii all equal R renders exactly as the radius setting R does, in every
 * image kind and with both kernels; a setting > 0 overrides the radii; the
 * thickness grows with the radius. Run with "fragment" and "compute", once per
 * surface splat (depth_pass.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_frame.h"
#include "render_fixture.h"
#include "test_util.h"

/* Pixels whose ray passes this close to a silhouette (relative to r²) may
 * round either way and are left out of the comparison. */
#define EDGE_SLACK 0.02
#define DEPTH_TOLERANCE 2e-4

static fc_code render_frame(render_fixture *f, const fc_frame *frame, const fc_camera *cam,
                            const fc_settings *settings, fc_aov aov, int want_u8, fc_image *out)
{
    fc_error err = {0};
    fc_code code = fc_pipeline_upload(f->pipeline, frame, NULL, &err);
    if (code == FC_OK)
        code = fc_pipeline_render(f->pipeline, cam, settings, aov, want_u8, out, NULL, &err);
    if (code != FC_OK)
        fprintf(stderr, "render failed: %s\n", err.message);
    return code;
}

/* Every pixel against the nearest analytic hit among spheres of their own radii. */
static void check_against_spheres(const fc_image *depth, const fc_camera *cam, const double (*centres)[3],
                                  const double *radii, int count)
{
    int wrong_coverage = 0, wrong_depth = 0, covered = 0;
    for (uint32_t row = 0; row < depth->height; row++)
        for (uint32_t x = 0; x < depth->width; x++) {
            double expected = 0.0;
            bool ambiguous = false;
            for (int i = 0; i < count; i++) {
                double edge;
                double d = analytic_sphere_depth(cam, centres[i], radii[i], x, row, &edge);
                ambiguous |= fabs(edge) < EDGE_SLACK;
                if (d > 0.0 && (expected == 0.0 || d < expected))
                    expected = d;
            }
            if (ambiguous)
                continue;
            double got = pixel_f32(depth, x, row);
            covered += got > 0.0;
            if ((expected == 0.0) != (got == 0.0))
                wrong_coverage++;
            else if (expected > 0.0 && fabs(got - expected) > DEPTH_TOLERANCE * expected)
                wrong_depth++;
        }
    CHECK_MSG(covered > 100, "only %d pixels show fluid", covered);
    CHECK_MSG(wrong_coverage == 0, "%d pixels disagree with the analytic silhouettes", wrong_coverage);
    CHECK_MSG(wrong_depth == 0, "%d pixels off the analytic depth", wrong_depth);
}

/* Covered pixels of the row through (x, row), walking left and right from x. */
static int run_width(const fc_image *depth, uint32_t x, uint32_t row)
{
    int width = 0;
    for (uint32_t i = x; i < depth->width && pixel_f32(depth, i, row) > 0.0f; i++)
        width++;
    for (uint32_t i = x; i-- > 0 && pixel_f32(depth, i, row) > 0.0f;)
        width++;
    return width;
}

/* Two particles at (-0.8, 0, 0) and (0.8, 0, 0) with radii 0.3 and 0.6: the
 * depth at each centre is distance - r_i, each silhouette's width is its own
 * projected diameter, every pixel is the analytic sphere of its own radius. */
static void test_two_radii(render_fixture *f)
{
    const uint32_t width = 161, height = 81;
    const double distance = 5.0;
    const double centres[2][3] = {{-0.8, 0.0, 0.0}, {0.8, 0.0, 0.0}};
    const double radii[2] = {0.3, 0.6};
    float positions[6] = {-0.8f, 0.0f, 0.0f, 0.8f, 0.0f, 0.0f};
    float radius[2] = {0.3f, 0.6f};
    fc_frame frame = {.count = 2, .positions = positions, .radius = radius};
    fc_camera cam = axis_camera(distance, width, height);
    fc_settings settings = test_settings(0.0f, FC_SMOOTHING_NONE, 0);   /* 0: the particles' own radii */
    fc_image depth = {0};
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    CHECK(fixture_splat_as_forced(f));
    if (depth.width != width) {
        fc_image_free(&depth);
        return;
    }
    check_against_spheres(&depth, &cam, centres, radii, 2);
    for (int i = 0; i < 2; i++) {
        double cx, crow;
        analytic_project(&cam, centres[i], &cx, &crow);
        uint32_t x = (uint32_t)cx, row = (uint32_t)crow;
        /* The centre pixel's ray is off the axis by under a pixel: the depth
         * there is the analytic hit, within a hair of distance - r_i. */
        double edge;
        double expected = analytic_sphere_depth(&cam, centres[i], radii[i], x, row, &edge);
        CHECK_NEAR(pixel_f32(&depth, x, row), expected, DEPTH_TOLERANCE * expected);
        CHECK_MSG(fabs(expected - (distance - radii[i])) < 0.01, "sphere %d: centre depth %g, distance - r %g", i,
                  expected, distance - radii[i]);
        /* The silhouette across the centre row: the projected diameter, to a pixel per side. */
        const double left[3] = {centres[i][0] - radii[i], 0.0, 0.0}, right[3] = {centres[i][0] + radii[i], 0.0, 0.0};
        double lx, rx, unused;
        analytic_project(&cam, left, &lx, &unused);
        analytic_project(&cam, right, &rx, &unused);
        int got = run_width(&depth, x, row);
        CHECK_MSG(fabs(got - (rx - lx)) <= 2.0, "sphere %d: %d pixels wide, projected diameter %.2f", i, got,
                  rx - lx);
    }
    fc_image_free(&depth);
}

/* A small blob: a 4x4x4 lattice with a little jitter, densities so a density
 * threshold makes two of them spray, velocities and ids for foam and colour. */
enum { BLOB = 64 };
static void fill_blob(fc_frame *frame, float radius_each)
{
    fc_error err;
    CHECK_CODE(fc_frame_alloc(frame, BLOB, FC_ATTR_ALL, &err), FC_OK);
    for (uint32_t i = 0; i < BLOB; i++) {
        float jitter = 0.01f * (float)((i * 37u) % 7u);
        frame->positions[3 * i] = 0.1f * (float)(i % 4) - 0.15f + jitter;
        frame->positions[3 * i + 1] = 0.1f * (float)(i / 4 % 4) - 0.15f;
        frame->positions[3 * i + 2] = 0.1f * (float)(i / 16) - 0.15f - jitter;
        frame->density[i] = i % 31 == 5 ? 100.0f : 1000.0f;
        frame->velocity[3 * i] = 0.2f * (float)(i % 3);
        frame->velocity[3 * i + 1] = 0.0f;
        frame->velocity[3 * i + 2] = -0.1f;
        frame->ids[i] = i;
        frame->radius[i] = radius_each;
    }
    frame->positions[3 * 5] += 0.4f;   /* the spray particles fly off */
    frame->positions[3 * 36 + 1] -= 0.3f;
}

static bool same_image(const fc_image *a, const fc_image *b)
{
    size_t bytes = (size_t)a->width * a->height * a->channels * (a->type == FC_PIXEL_U8 ? 1 : 4);
    return a->width == b->width && a->height == b->height && a->channels == b->channels && a->type == b->type &&
           memcmp(a->pixels, b->pixels, bytes) == 0;
}

/* How many pixels of two images differ. */
static size_t differing_pixels(const fc_image *a, const fc_image *b)
{
    size_t per_pixel = (size_t)a->channels * (a->type == FC_PIXEL_U8 ? 1 : 4), n = 0;
    for (size_t i = 0; i < (size_t)a->width * a->height; i++)
        n += memcmp((const uint8_t *)a->pixels + i * per_pixel, (const uint8_t *)b->pixels + i * per_pixel,
                    per_pixel) != 0;
    return n;
}

/* Pixels of two RGBA8 images whose colours differ by more than `threshold`
 * (summed over the channels): what a droplet covers, not the last-bit changes
 * of a view whose depth range followed the largest particle. */
static size_t visibly_differing_pixels(const fc_image *a, const fc_image *b, int threshold)
{
    size_t n = 0;
    const uint8_t *p = a->pixels, *q = b->pixels;
    for (size_t i = 0; i < (size_t)a->width * a->height; i++) {
        int d = 0;
        for (int c = 0; c < 3; c++)
            d += abs((int)p[4 * i + c] - (int)q[4 * i + c]);
        n += d > threshold;
    }
    return n;
}

/* The full look: smoothing, shadow, spray, noise and foam, colour by speed. */
static fc_settings full_settings(float radius, fc_kernel kernel)
{
    fc_settings s;
    fc_settings_default(&s);
    s.radius = radius;
    s.kernel = kernel;
    s.noise = 0.5f;
    s.foam = 1.0f;
    s.density_threshold = 500.0f;
    return s;
}

/* Radii all R with the setting 0 against no radii with the setting R: the
 * same image, bit for bit, in every image kind, with either kernel. Then a
 * setting > 0 overrides radii that differ. */
static void test_equal_radii_are_the_setting(render_fixture *f)
{
    const float R = 0.06f;
    fc_camera cam = axis_camera(1.5, 96, 64);
    cam.eye[1] = -0.6f;   /* from above the floor a little, so the shadow shows */
    fc_frame with_radii, plain;
    fill_blob(&with_radii, R);
    plain = with_radii;
    plain.radius = NULL;
    const fc_aov aovs[] = {FC_AOV_COLOR, FC_AOV_DEPTH, FC_AOV_SMOOTHED_DEPTH, FC_AOV_THICKNESS, FC_AOV_NORMAL,
                           FC_AOV_NOISE};
    const char *names[] = {"color", "depth", "smoothed depth", "thickness", "normal", "noise"};
    for (int k = 0; k < 2; k++) {
        fc_kernel kernel = k ? FC_KERNEL_ANISOTROPIC : FC_KERNEL_SPHERE;
        for (size_t a = 0; a < sizeof aovs / sizeof aovs[0]; a++) {
            fc_settings by_radii = full_settings(0.0f, kernel), by_setting = full_settings(R, kernel);
            fc_image x = {0}, y = {0};
            CHECK_CODE(render_frame(f, &with_radii, &cam, &by_radii, aovs[a], 1, &x), FC_OK);
            CHECK_CODE(render_frame(f, &plain, &cam, &by_setting, aovs[a], 1, &y), FC_OK);
            CHECK_MSG(same_image(&x, &y), "%s kernel, %s: %zu pixels differ", k ? "anisotropic" : "sphere", names[a],
                      x.pixels && y.pixels ? differing_pixels(&x, &y) : 0);
            fc_image_free(&x);
            fc_image_free(&y);
        }
    }
    /* Radii from 0.5 R to 1.5 R, overridden by the setting R: as if there were none. */
    for (uint32_t i = 0; i < BLOB; i++)
        with_radii.radius[i] = R * (0.5f + (float)(i % 5) * 0.25f);
    fc_settings override = full_settings(R, FC_KERNEL_SPHERE), own = full_settings(0.0f, FC_KERNEL_SPHERE);
    fc_image x = {0}, y = {0}, z = {0};
    CHECK_CODE(render_frame(f, &with_radii, &cam, &override, FC_AOV_COLOR, 1, &x), FC_OK);
    CHECK_CODE(render_frame(f, &plain, &cam, &override, FC_AOV_COLOR, 1, &y), FC_OK);
    CHECK_MSG(same_image(&x, &y), "the setting R does not override the radii: %zu pixels differ",
              x.pixels && y.pixels ? differing_pixels(&x, &y) : 0);
    /* ... and without the override the varied radii show. */
    CHECK_CODE(render_frame(f, &with_radii, &cam, &own, FC_AOV_COLOR, 1, &z), FC_OK);
    CHECK_MSG(z.pixels && y.pixels && differing_pixels(&z, &y) > 100, "varied radii changed %zu pixels only",
              z.pixels && y.pixels ? differing_pixels(&z, &y) : 0);
    fc_image_free(&x);
    fc_image_free(&y);
    fc_image_free(&z);
    fc_frame_free(&with_radii);
}

/* One sphere of radius r, then 2r: its thickness at the centre is the chord
 * through it, its diameter, so it doubles. */
static void test_thickness_scales_with_radius(render_fixture *f)
{
    const uint32_t size = 65;
    fc_camera cam = axis_camera(5.0, size, size);
    fc_settings settings = test_settings(0.0f, FC_SMOOTHING_NONE, 0);
    float position[3] = {0.0f, 0.0f, 0.0f};
    float thickness[2];
    for (int i = 0; i < 2; i++) {
        float radius = 0.25f * (float)(i + 1);
        fc_frame frame = {.count = 1, .positions = position, .radius = &radius};
        fc_image img = {0};
        CHECK_CODE(render_frame(f, &frame, &cam, &settings, FC_AOV_THICKNESS, 0, &img), FC_OK);
        thickness[i] = img.pixels ? pixel_f32(&img, size / 2, size / 2) : 0.0f;
        /* Blurred by the default blur of a few pixels, the centre keeps most of the diameter. */
        CHECK_MSG(thickness[i] > 0.8f * 2.0f * radius && thickness[i] <= 2.0f * radius * 1.001f,
                  "radius %g: thickness %g at the centre", (double)radius, (double)thickness[i]);
        fc_image_free(&img);
    }
    CHECK_MSG(thickness[1] > 1.9f * thickness[0], "thickness %g at radius 0.25, %g at 0.5", (double)thickness[0],
              (double)thickness[1]);
}

/* A spray droplet (particle 5, below the density threshold) drawn at its own
 * radius: the pixels it changes, against the same frame with the droplet
 * shrunk to nothing, grow with the square of its radius. */
static void test_spray_droplet_size(render_fixture *f)
{
    const float R = 0.06f;
    fc_camera cam = axis_camera(1.2, 256, 192);
    fc_frame frame;
    fill_blob(&frame, R);
    frame.radius[36] = 1e-5f;   /* the other droplet out of the way */
    fc_settings settings = full_settings(0.0f, FC_KERNEL_SPHERE);
    settings.noise = 0.0f;
    fc_image none = {0};
    frame.radius[5] = 1e-5f;
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, FC_AOV_COLOR, 1, &none), FC_OK);
    size_t changed[2] = {0, 0};
    for (int i = 0; i < 2; i++) {
        frame.radius[5] = R * (float)(i + 1);
        fc_image img = {0};
        CHECK_CODE(render_frame(f, &frame, &cam, &settings, FC_AOV_COLOR, 1, &img), FC_OK);
        changed[i] = img.pixels && none.pixels ? visibly_differing_pixels(&img, &none, 12) : 0;
        fc_image_free(&img);
    }
    double ratio = changed[0] ? (double)changed[1] / (double)changed[0] : 0.0;
    printf("spray droplet: radius R changes %zu pixels, 2R %zu\n", changed[0], changed[1]);
    CHECK_MSG(changed[0] > 4 && ratio > 2.5 && ratio < 6.0, "droplet of radius R changed %zu pixels, 2R %zu",
              changed[0], changed[1]);
    fc_image_free(&none);
    fc_frame_free(&frame);
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    test_two_radii(&f);
    test_thickness_scales_with_radius(&f);
    test_equal_radii_are_the_setting(&f);
    test_spray_droplet_size(&f);
    fixture_close(&f);
    return test_result();
}
