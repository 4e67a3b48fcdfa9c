/* test_splat_agreement.c — the two surface splats (depth_pass.h) on a dense
 * random cloud of small spheres, tens of them over many pixels: the same
 * coverage and bit for bit the same nearest depth (both take the minimum of
 * the same ray casts), and thickness sums equal up to summation order and
 * the compute splat's fixed point. A pixel either splat loses at a
 * silhouette shows as a depth or coverage difference. With spheres about 6
 * pixels across (splat_walk_rows.glsl), twice with spheres of two or three
 * (splat_walk_small.glsl), and twice with spheres under a pixel across,
 * where whether a sphere covers a pixel centre at all is decided at the
 * edge of the compute splat's bounding box, and which the compute splat
 * walks without loops (splat_walk_tiny.glsl). At half the resolution, the
 * compute splat's footprint thickness of small spheres against the spheres'
 * volume. The analytic checks
 * of each splat are in test_sphere_depth.c and test_thickness.c. */
#include <math.h>
#include <stdio.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define PARTICLES 40000
#define WIDTH 400
#define HEIGHT 240
/* Spheres about 6 pixels across at the cloud's centre (walked by rows),
 * about 2.6 (nine candidates and loops), and about 0.9. */
#define RADIUS_ROWS 0.023f
#define RADIUS_LARGE 0.01f
#define RADIUS_SMALL 0.0015f
/* About 0.75 pixel across at the centre, 0.9 at the nearest: boxes of up to
 * 2x2 pixel centres, the most the compute splat's loop-free walk takes. */
#define RADIUS_TWO_BY_TWO 0.0028f
/* About 2.2 pixels across at the centre, 2.8 at the nearest: the typical
 * box holds up to 3x3 pixel centres, walked by splat_walk_small.glsl's nine
 * candidates, the nearest spheres' boxes of 4 by its loops (those of
 * RADIUS_LARGE hold up to 4x4). */
#define RADIUS_THREE_BY_THREE 0.0085f

/* A deterministic cloud in the unit cube (a 32-bit LCG: the same on every platform). */
static void random_cloud(float *positions, int count)
{
    uint32_t state = 12345u;
    for (int i = 0; i < 3 * count; i++) {
        state = state * 1664525u + 1013904223u;
        positions[i] = (float)(state >> 8) / 16777216.0f - 0.5f;
    }
}

static void render_both(render_fixture *f, const float *positions, float radius, fc_aov aov, fc_image *fragment,
                        fc_image *compute)
{
    fc_camera cam = axis_camera(2.5, WIDTH, HEIGHT);
    fc_settings settings = test_settings(radius, FC_SMOOTHING_NONE, 0);
    fc_pipeline_force_splat(f->pipeline, FC_SPLAT_FRAGMENT);
    CHECK_CODE(render_positions(f, positions, PARTICLES, &cam, &settings, aov, 0, fragment), FC_OK);
    CHECK(fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_FRAGMENT);
    fc_pipeline_force_splat(f->pipeline, FC_SPLAT_COMPUTE);
    CHECK_CODE(render_positions(f, positions, PARTICLES, &cam, &settings, aov, 0, compute), FC_OK);
    CHECK(fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_COMPUTE);
}

static void test_same_depth(render_fixture *f, const float *positions, float radius, int min_covered)
{
    fc_image a = {0}, b = {0};
    render_both(f, positions, radius, FC_AOV_DEPTH, &a, &b);
    /* Spheres under a pixel across are walked without loops (at most 2x2 pixels each), those about two
     * pixels across by nine candidates and loops beyond them. */
    fc_splat_walk walk = radius == RADIUS_ROWS                                      ? FC_SPLAT_WALK_ROWS
                         : radius == RADIUS_LARGE || radius == RADIUS_THREE_BY_THREE ? FC_SPLAT_WALK_SMALL
                                                                                     : FC_SPLAT_WALK_TINY;
    CHECK_MSG(fc_pipeline_last_splat_walk(f->pipeline) == walk, "radius %g: walk %d, not %d", radius,
              (int)fc_pipeline_last_splat_walk(f->pipeline), (int)walk);
    int covered = 0, differ = 0;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++) {
            covered += pixel_f32(&a, x, row) > 0.0f;
            differ += pixel_f32(&a, x, row) != pixel_f32(&b, x, row);
        }
    CHECK_MSG(covered > min_covered, "only %d pixels covered at radius %g", covered, radius);
    CHECK_MSG(differ == 0, "%d of %d covered pixels differ in depth at radius %g", differ, covered, radius);
    fc_image_free(&a);
    fc_image_free(&b);
}

static void test_same_thickness(render_fixture *f, const float *positions, float radius, float min_spheres_deep)
{
    fc_image a = {0}, b = {0};
    render_both(f, positions, radius, FC_AOV_THICKNESS, &a, &b);
    int differ = 0;
    float deepest = 0.0f;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++) {
            float p = pixel_f32(&a, x, row), q = pixel_f32(&b, x, row);
            deepest = fmaxf(deepest, p);
            differ += (p == 0.0f) != (q == 0.0f) || fabsf(p - q) > 1e-5f * p + 1e-7f;
        }
    /* Several spheres deep somewhere: the sums are really sums. */
    CHECK_MSG(deepest > min_spheres_deep * 2 * radius, "thickest pixel %g at radius %g", deepest, radius);
    CHECK_MSG(differ == 0, "%d pixels differ in thickness at radius %g", differ, radius);
    fc_image_free(&a);
    fc_image_free(&b);
}

/* The thickness at half resolution, where the compute splat spreads a
 * small sphere's volume over the pixels of its projected footprint (an
 * ellipse over which the chord falls off as 2r sqrt(1 - offset^2), widened
 * to a pixel's radius where the sphere is narrower) instead of casting a ray
 * per pixel as the fragment splat does, whose chords at pixel centres add
 * more or less than the sphere by where it falls between them. Over the
 * image the thickness sums to every sphere's volume over the area a pixel
 * spans at its depth (times 1 / cos of its angle off the view axis, as the
 * rays through it are slanted): the spheres narrower than a pixel too. */
static void test_footprint_volume(render_fixture *f, const float *positions, float radius)
{
    fc_camera cam = axis_camera(2.5, WIDTH, HEIGHT);
    fc_settings settings = test_settings(radius, FC_SMOOTHING_NONE, 0);
    settings.thickness_scale = 0.5f;
    fc_image img = {0};
    fc_pipeline_force_splat(f->pipeline, FC_SPLAT_COMPUTE);
    CHECK_CODE(render_positions(f, positions, PARTICLES, &cam, &settings, FC_AOV_THICKNESS, 0, &img), FC_OK);
    CHECK(fc_pipeline_last_splat_walk(f->pipeline) != FC_SPLAT_WALK_ROWS);
    double sum = 0.0;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++)
            sum += pixel_f32(&img, x, row);
    /* The AOV has the view's pixels, each spanning 2 d tan(fov / 2) / HEIGHT at depth d. */
    const double volume = 4.0 / 3.0 * M_PI * pow(radius, 3.0);
    const double span = 2.0 * tan(0.5 * cam.fov_y_deg * M_PI / 180.0) / HEIGHT;
    double expected = 0.0;
    for (int i = 0; i < PARTICLES; i++) {
        const float *p = positions + 3 * i;
        double depth = cam.eye[2] - p[2];
        double distance = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + depth * depth);
        expected += volume / (span * depth * span * depth) * distance / depth;
    }
    /* Measured: 1.00011-1.00012 at every radius (the ray casts: 0.960-1.002). */
    CHECK_MSG(fabs(sum / expected - 1.0) < 1e-3, "the thickness sums to %.5f of the spheres' volume at radius %g",
              sum / expected, radius);
    fc_image_free(&img);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    static float positions[3 * PARTICLES];
    random_cloud(positions, PARTICLES);
    /* Depth only: sums hundreds of spheres deep carry more of the compute splat's fixed point than the
     * thickness check allows, and the thickness's arithmetic is the same at every walk. */
    test_same_depth(&f, positions, RADIUS_ROWS, WIDTH * HEIGHT / 4);
    test_same_depth(&f, positions, RADIUS_LARGE, WIDTH * HEIGHT / 10);
    test_same_thickness(&f, positions, RADIUS_LARGE, 10);
    test_same_depth(&f, positions, RADIUS_SMALL, WIDTH * HEIGHT / 40);
    test_same_thickness(&f, positions, RADIUS_SMALL, 2);
    test_same_depth(&f, positions, RADIUS_TWO_BY_TWO, WIDTH * HEIGHT / 20);
    test_same_thickness(&f, positions, RADIUS_TWO_BY_TWO, 2);
    test_same_depth(&f, positions, RADIUS_THREE_BY_THREE, WIDTH * HEIGHT / 10);
    test_same_thickness(&f, positions, RADIUS_THREE_BY_THREE, 4);
    test_footprint_volume(&f, positions, RADIUS_SMALL);
    test_footprint_volume(&f, positions, RADIUS_TWO_BY_TWO);
    test_footprint_volume(&f, positions, RADIUS_THREE_BY_THREE);
    test_footprint_volume(&f, positions, RADIUS_LARGE);
    fixture_close(&f);
    return test_result();
}
