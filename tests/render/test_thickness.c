/* test_thickness.c — the thickness pass: one sphere on the view axis is 2r
 * thick at its centre and follows the analytic chord elsewhere; k spheres
 * stacked along the axis are k times as thick, and so are k spheres in one
 * place, up to thousands (the compute splat sums in fixed point). Run with
 * "fragment" and "compute", once per surface splat (depth_pass.h). */
#include <math.h>

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

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    test_single_sphere(&f);
    test_stacks_add_up(&f);
    test_coincident_spheres_add_up(&f);
    CHECK(fixture_splat_as_forced(&f));
    fixture_close(&f);
    return test_result();
}
