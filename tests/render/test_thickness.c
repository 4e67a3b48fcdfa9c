/* test_thickness.c — the thickness pass: one sphere on the view axis is 2r
 * thick at its centre and follows the analytic chord elsewhere; k spheres
 * stacked along the axis are k times as thick, and so are k spheres in one
 * place, up to thousands (the compute splat sums in fixed point). Spheres of
 * a pixel or two at the default half-resolution thickness (which the compute
 * splat takes from their projected footprint instead of a ray cast per
 * pixel) hold their volume: the thickness summed over the image times a
 * pixel's area is the spheres' volume. Run with "fragment" and "compute",
 * once per surface splat (depth_pass.h). */
#include <math.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define SIZE 65              /* odd: pixel 32 sits on the view axis */
#define RADIUS 0.25
#define SPACING 0.6          /* between stacked centres: the spheres do not touch */

/* Thickness image of `count` spheres stacked on the view axis, the first at
 * the origin, the others towards the camera. */
static fc_code render_stack(render_fixture *f, int count, fc_image *out)
{
    float positions[3 * 8] = {0};
    for (int i = 0; i < count; i++)
        positions[3 * i + 2] = (float)(SPACING * i);
    fc_camera cam = axis_camera(6.0, SIZE, SIZE);
    fc_settings settings = test_settings((float)RADIUS, FC_SMOOTHING_NONE, 0);
    return render_positions(f, positions, (uint64_t)count, &cam, &settings, FC_AOV_THICKNESS, 0, out);
}

static void test_single_sphere(render_fixture *f)
{
    fc_image one = {0};
    CHECK_CODE(render_stack(f, 1, &one), FC_OK);
    CHECK(one.channels == 1 && one.type == FC_PIXEL_F32);
    CHECK_NEAR(pixel_f32(&one, 32, 32), 2.0 * RADIUS, 1e-4);
    CHECK(pixel_f32(&one, 0, 0) == 0.0f);

    /* Off centre: the chord 2·sqrt(r² - m²) of the ray passing m from the centre. */
    fc_camera cam = axis_camera(6.0, SIZE, SIZE);
    const double centre[3] = {0.0, 0.0, 0.0};
    double edge;
    analytic_sphere_depth(&cam, centre, RADIUS, 34, 31, &edge);
    CHECK(edge > 0.1 && edge < 0.95);
    CHECK_NEAR(pixel_f32(&one, 34, 31), 2.0 * RADIUS * sqrt(edge), 1e-4);
    fc_image_free(&one);
}

static void test_stacks_add_up(render_fixture *f)
{
    fc_image one = {0}, stack = {0};
    CHECK_CODE(render_stack(f, 1, &one), FC_OK);
    for (int k = 2; k <= 4; k++) {
        CHECK_CODE(render_stack(f, k, &stack), FC_OK);
        CHECK_NEAR(pixel_f32(&stack, 32, 32), k * pixel_f32(&one, 32, 32), 1e-4 * k);
    }
    fc_image_free(&one);
    fc_image_free(&stack);
}

static void test_coincident_spheres_add_up(render_fixture *f)
{
    enum { COUNT = 5000 };
    static float positions[3 * COUNT];   /* all at the origin */
    fc_camera cam = axis_camera(6.0, SIZE, SIZE);
    fc_settings settings = test_settings((float)RADIUS, FC_SMOOTHING_NONE, 0);
    fc_image img = {0};
    CHECK_CODE(render_positions(f, positions, COUNT, &cam, &settings, FC_AOV_THICKNESS, 0, &img), FC_OK);
    CHECK_NEAR(pixel_f32(&img, 32, 32), COUNT * 2.0 * RADIUS, 1e-5 * COUNT * 2.0 * RADIUS);
    CHECK(pixel_f32(&img, 0, 0) == 0.0f);
    fc_image_free(&img);
}

/* A jittered grid of spheres about 1.7 pixels across at the thickness's
 * half resolution, apart from each other, around the plane z = 0 facing the
 * camera. Along a ray at angle theta to the view axis a pixel of the plane
 * at depth d holds a slab of area A(d) cos(theta) across the ray, so the
 * thickness summed over the image times A(d) is the volume over
 * cos(theta), sphere by sphere. Each sphere's pixel centres fall at another
 * phase, so the sum's sampling error (up to tens of percent for one sphere
 * this small) averages out over the grid; no pixel is thicker than a
 * diameter. */
#define GRID 15
#define GRID_SPACING 0.13
#define GRID_JITTER 0.02
#define SMALL_RADIUS 0.03
#define GRID_DISTANCE 6.0
#define GRID_WIDTH 320
#define GRID_HEIGHT 240

static void test_small_spheres_hold_their_volume(render_fixture *f)
{
    float positions[3 * GRID * GRID];
    const double pi = 3.14159265358979;
    const double volume = 4.0 / 3.0 * pi * pow(SMALL_RADIUS, 3);
    /* A pixel's side at depth d: 2 d tan(fov / 2) / height, the fov 40 degrees. */
    const double side_per_depth = 2.0 * tan(20.0 * pi / 180.0) / GRID_HEIGHT;
    double expected = 0.0;
    uint32_t state = 2024u;
    for (int n = 0; n < GRID * GRID; n++) {
        float *x = &positions[3 * n];
        for (int k = 0; k < 3; k++) {
            state = state * 1664525u + 1013904223u;
            double jitter = ((double)(state >> 8) / 16777216.0 - 0.5) * 2.0 * GRID_JITTER;
            double cell = k == 0 ? n % GRID - GRID / 2 : k == 1 ? n / GRID - GRID / 2 : 0;
            x[k] = (float)(cell * GRID_SPACING + jitter);
        }
        double depth = GRID_DISTANCE - x[2], lateral2 = (double)x[0] * x[0] + (double)x[1] * x[1];
        double area = pow(side_per_depth * depth, 2);
        expected += volume / area * sqrt(1.0 + lateral2 / (depth * depth));   /* volume / cos(theta) / A(d) */
    }
    fc_camera cam = axis_camera(GRID_DISTANCE, GRID_WIDTH, GRID_HEIGHT);
    fc_settings settings = test_settings((float)SMALL_RADIUS, FC_SMOOTHING_NONE, 0);
    settings.thickness_scale = 0.5f;
    fc_image img = {0};
    CHECK_CODE(render_positions(f, positions, GRID * GRID, &cam, &settings, FC_AOV_THICKNESS, 0, &img), FC_OK);
    if (f->splat != FC_SPLAT_FRAGMENT)
        CHECK_MSG(fc_pipeline_last_splat_walk(f->pipeline) != FC_SPLAT_WALK_ROWS, "the thickness took the rows walk");
    double sum = 0.0, thickest = 0.0;
    for (uint32_t row = 0; row < GRID_HEIGHT; row++)
        for (uint32_t x = 0; x < GRID_WIDTH; x++) {
            sum += pixel_f32(&img, x, row);
            thickest = fmax(thickest, pixel_f32(&img, x, row));
        }
    /* Measured: 0.995 with either splat. */
    CHECK_MSG(fabs(sum / expected - 1.0) < 0.03, "the spheres hold %.4f of their volume", sum / expected);
    CHECK_MSG(thickest > 0.5 * SMALL_RADIUS && thickest <= 2.0 * SMALL_RADIUS * (1.0 + 1e-4),
              "thickest pixel %g for spheres of diameter %g", thickest, 2.0 * SMALL_RADIUS);
    fc_image_free(&img);
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    test_single_sphere(&f);
    test_stacks_add_up(&f);
    test_coincident_spheres_add_up(&f);
    test_small_spheres_hold_their_volume(&f);
    CHECK(fixture_splat_as_forced(&f));
    fixture_close(&f);
    return test_result();
}
