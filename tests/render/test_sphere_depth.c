/* test_sphere_depth.c — the depth pass against analytic spheres: projected
 * disc size and centre, linear depth at and off the centre, background 0,
 * exact silhouettes off axis, the nearest sphere winning, a sphere whose
 * centre lies outside the image, and a close-up larger than point sprites
 * can be (GL_POINT_SIZE_RANGE ends at 255 pixels on llvmpipe). Run with
 * "fragment" and "compute", once per surface splat (depth_pass.h); the
 * choice between them by sprite size is tested here too. */
#include <math.h>
#include <stdio.h>

#include "depth_pass.h"
#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"
#include "view.h"

static const double PI = 3.14159265358979323846;

/* Pixels whose ray passes this close to a silhouette (relative to r²) may
 * round either way and are left out of the coverage comparison. */
#define EDGE_SLACK 0.02
#define DEPTH_TOLERANCE 2e-4

typedef struct sphere {
    double centre[3];
} sphere;

/* Compares every pixel with the nearest analytic hit among the spheres:
 * background exactly 0 where all miss, the front depth where one hits. */
static void check_against_spheres(const fc_image *depth, const fc_camera *cam, const sphere *spheres, int count,
                                  double radius)
{
    int wrong_coverage = 0, wrong_depth = 0;
    double worst = 0.0;
    for (uint32_t row = 0; row < depth->height; row++) {
        for (uint32_t x = 0; x < depth->width; x++) {
            double expected = 0.0;
            bool ambiguous = false;
            for (int i = 0; i < count; i++) {
                double edge;
                double d = analytic_sphere_depth(cam, spheres[i].centre, radius, x, row, &edge);
                ambiguous |= fabs(edge) < EDGE_SLACK;
                if (d > 0.0 && (expected == 0.0 || d < expected))
                    expected = d;
            }
            if (ambiguous)
                continue;
            double got = pixel_f32(depth, x, row);
            if ((expected == 0.0) != (got == 0.0))
                wrong_coverage++;
            else if (expected > 0.0 && fabs(got - expected) > DEPTH_TOLERANCE * expected)
                wrong_depth++;
            if (expected > 0.0 && got > 0.0)
                worst = fmax(worst, fabs(got - expected));
        }
    }
    CHECK_MSG(wrong_coverage == 0, "%d pixels disagree with the analytic silhouette", wrong_coverage);
    CHECK_MSG(wrong_depth == 0, "%d pixels off the analytic depth (worst %g)", wrong_depth, worst);
}

static void test_on_axis_sphere(render_fixture *f)
{
    /* Odd size: pixel 64 is centred on the view axis. */
    const uint32_t size = 129;
    const double distance = 5.0, radius = 0.5;
    fc_camera cam = axis_camera(distance, size, size);
    fc_settings settings = test_settings((float)radius, FC_SMOOTHING_NONE, 0);
    const float position[3] = {0.0f, 0.0f, 0.0f};
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, position, 1, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    CHECK(depth.width == size && depth.height == size && depth.channels == 1 && depth.type == FC_PIXEL_F32);

    /* Front of the sphere on the axis: centre distance minus r. */
    CHECK_NEAR(pixel_f32(&depth, 64, 64), distance - radius, 1e-4);
    /* Off centre, 10 pixels right and 6 up: the analytic ray-sphere hit. */
    double edge;
    const sphere s = {{0.0, 0.0, 0.0}};
    double expected = analytic_sphere_depth(&cam, s.centre, radius, 74, 58, &edge);
    CHECK(expected > distance - radius + 0.01);
    CHECK_NEAR(pixel_f32(&depth, 74, 58), expected, 1e-4);
    CHECK(pixel_f32(&depth, 0, 0) == 0.0f);

    /* The silhouette is a circle of radius f·r/sqrt(d² - r²) in NDC. */
    double fy = 1.0 / tan(cam.fov_y_deg * PI / 360.0);
    double expected_radius_px = 0.5 * size * fy * radius / sqrt(distance * distance - radius * radius);
    double covered = 0.0, sum_x = 0.0, sum_row = 0.0;
    for (uint32_t row = 0; row < size; row++)
        for (uint32_t x = 0; x < size; x++)
            if (pixel_f32(&depth, x, row) > 0.0f) {
                covered += 1.0;
                sum_x += x + 0.5;
                sum_row += row + 0.5;
            }
    CHECK_NEAR(sqrt(covered / PI), expected_radius_px, 0.5);
    double centre_x, centre_row;
    analytic_project(&cam, s.centre, &centre_x, &centre_row);
    CHECK_NEAR(sum_x / covered, centre_x, 0.1);
    CHECK_NEAR(sum_row / covered, centre_row, 0.1);

    check_against_spheres(&depth, &cam, &s, 1, radius);
    fc_image_free(&depth);
}

/* Far off axis the silhouette is an ellipse pushed outwards; a sprite sized by
 * r/depth alone would cut it. Non-square so the aspect ratio is exercised. */
static void test_off_axis_sphere(render_fixture *f)
{
    fc_camera cam = axis_camera(4.0, 128, 96);
    fc_settings settings = test_settings(0.45f, FC_SMOOTHING_NONE, 0);
    const sphere s = {{1.55, 0.85, 0.3}};
    const float position[3] = {1.55f, 0.85f, 0.3f};
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, position, 1, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    check_against_spheres(&depth, &cam, &s, 1, 0.45);
    double x, row;
    analytic_project(&cam, s.centre, &x, &row);
    CHECK(x > 96.0 && row < 24.0);   /* really in the upper right */
    fc_image_free(&depth);
}

/* The hardware depth test keeps the sphere nearest the camera. Drawn far one
 * last, so a missing depth test would show it. */
static void test_nearest_sphere_wins(render_fixture *f)
{
    fc_camera cam = axis_camera(5.0, 96, 96);
    fc_settings settings = test_settings(0.5f, FC_SMOOTHING_NONE, 0);
    const sphere spheres[2] = {{{0.3, 0.1, 1.0}}, {{0.0, 0.0, 0.0}}};
    const float positions[6] = {0.3f, 0.1f, 1.0f, 0.0f, 0.0f, 0.0f};
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, positions, 2, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    check_against_spheres(&depth, &cam, spheres, 2, 0.5);
    fc_image_free(&depth);
}

static int covered_pixels(const fc_image *depth)
{
    int covered = 0;
    for (uint32_t row = 0; row < depth->height; row++)
        for (uint32_t x = 0; x < depth->width; x++)
            covered += pixel_f32(depth, x, row) > 0.0f;
    return covered;
}

/* The first centre is 0.2 beyond the right edge of the view at the sphere's
 * depth, the sphere reaches 0.3 into it: its visible part must be there,
 * exact. The second sphere, wholly in view, is drawn the other way (a point
 * sprite, see sphere.vert.glsl) in the same draw. */
static void test_centre_outside_image(render_fixture *f)
{
    fc_camera cam = axis_camera(5.0, 96, 64);
    const double radius = 0.5;
    fc_settings settings = test_settings((float)radius, FC_SMOOTHING_NONE, 0);
    double half_width = 5.0 * tan(cam.fov_y_deg * PI / 360.0) * 96.0 / 64.0;
    const sphere spheres[2] = {{{half_width + 0.2, 0.0, 0.0}}, {{-0.5, 0.2, 0.0}}};
    const float positions[6] = {(float)spheres[0].centre[0], 0.0f, 0.0f, -0.5f, 0.2f, 0.0f};
    double x, row;
    analytic_project(&cam, spheres[0].centre, &x, &row);
    CHECK(x > 96.0);
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, positions, 1, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    int edge_only = covered_pixels(&depth);
    CHECK_MSG(edge_only > 50, "%d pixels show the sphere", edge_only);
    check_against_spheres(&depth, &cam, spheres, 1, radius);
    CHECK_CODE(render_positions(f, positions, 2, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    CHECK(covered_pixels(&depth) > edge_only + 100);
    check_against_spheres(&depth, &cam, spheres, 2, radius);
    fc_image_free(&depth);
}

/* 1 unit from the camera a sphere of radius 0.5 spans about 390 of 400
 * pixels: complete, with its analytic depth everywhere. */
static void test_close_up_larger_than_point_sprites(render_fixture *f)
{
    const uint32_t size = 400;
    fc_camera cam = axis_camera(1.5, size, size);
    const double radius = 0.5;
    fc_settings settings = test_settings((float)radius, FC_SMOOTHING_NONE, 0);
    const sphere s = {{0.0, 0.0, 0.0}};
    const float position[3] = {0.0f, 0.0f, 0.0f};
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, position, 1, &cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    double fy = 1.0 / tan(cam.fov_y_deg * PI / 360.0);
    double diameter_px = size * fy * radius / sqrt(1.5 * 1.5 - radius * radius);
    CHECK(diameter_px > 300.0 && diameter_px < size);
    /* Too large for the compute splat: the fragment splat draws it even where the compute splat is forced. */
    CHECK(fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_FRAGMENT);
    CHECK_NEAR(sqrt(covered_pixels(&depth) / PI), 0.5 * diameter_px, 0.5);
    check_against_spheres(&depth, &cam, &s, 1, radius);
    fc_image_free(&depth);
}

/* The automatic choice: the compute splat for small sprites only, never for
 * a view from inside the particles or with a sphere near the camera, where
 * forcing the compute splat gets the fragment splat too. */
static void test_choice_by_sprite_size(void)
{
    const float lo[3] = {-0.5f, -0.5f, -0.5f}, hi[3] = {0.5f, 0.5f, 0.5f};
    const float radius = 0.01f;
    fc_view view;
    /* 0.01 at 5 units, 40 degrees over 360 rows: 2 r f H / 2 d = 0.01 · 2.747 · 360 / 5 = 2.0 px. */
    fc_camera cam = axis_camera(5.0, 640, 360);
    fc_view_from_camera(&cam, lo, hi, radius, &view);
    CHECK(fc_depth_pass_choose(&view, lo, hi, radius, FC_SPLAT_AUTO) == FC_SPLAT_COMPUTE);
    CHECK(fc_depth_pass_choose(&view, lo, hi, radius, FC_SPLAT_FRAGMENT) == FC_SPLAT_FRAGMENT);
    /* 20 times the radius: 40 px across, still the compute splat's; 40 times: 80 px. */
    fc_view_from_camera(&cam, lo, hi, 20.0f * radius, &view);
    CHECK(fc_depth_pass_choose(&view, lo, hi, 20.0f * radius, FC_SPLAT_AUTO) == FC_SPLAT_COMPUTE);
    fc_view_from_camera(&cam, lo, hi, 40.0f * radius, &view);
    CHECK(fc_depth_pass_choose(&view, lo, hi, 40.0f * radius, FC_SPLAT_AUTO) == FC_SPLAT_FRAGMENT);
    CHECK(fc_depth_pass_choose(&view, lo, hi, 40.0f * radius, FC_SPLAT_COMPUTE) == FC_SPLAT_COMPUTE);
    /* Half the radius, seen from 0.52: 9.5 px at the centre's depth, but the
     * nearest particles may lie 0.02 from the eye, 250 px across. */
    cam = axis_camera(0.52, 640, 360);
    fc_view_from_camera(&cam, lo, hi, 0.5f * radius, &view);
    CHECK(fc_depth_pass_choose(&view, lo, hi, 0.5f * radius, FC_SPLAT_AUTO) == FC_SPLAT_FRAGMENT);
    CHECK(fc_depth_pass_choose(&view, lo, hi, 0.5f * radius, FC_SPLAT_COMPUTE) == FC_SPLAT_FRAGMENT);
    cam = axis_camera(0.9, 640, 360);
    fc_view_from_camera(&cam, lo, hi, 0.5f * radius, &view);
    CHECK(fc_depth_pass_choose(&view, lo, hi, 0.5f * radius, FC_SPLAT_AUTO) == FC_SPLAT_COMPUTE);
    /* The eye inside the particles. */
    cam = axis_camera(0.3, 640, 360);
    fc_view_from_camera(&cam, lo, hi, radius, &view);
    CHECK(fc_depth_pass_choose(&view, lo, hi, radius, FC_SPLAT_AUTO) == FC_SPLAT_FRAGMENT);
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    test_on_axis_sphere(&f);
    test_off_axis_sphere(&f);
    test_nearest_sphere_wins(&f);
    test_centre_outside_image(&f);
    CHECK(fixture_splat_as_forced(&f));
    test_close_up_larger_than_point_sprites(&f);
    test_choice_by_sprite_size();
    fixture_close(&f);
    return test_result();
}
