/* test_surface_render.c — `--surface mesh` renders (surface_raster.h)
 * through real GL: a lone particle's mesh is its sphere, so the depth image
 * matches the analytic sphere's depth pixel for pixel (as the splats' depth
 * does in test_sphere_depth), 0 off the sphere, and the thickness image its
 * chords; a frame whose grid passes the budget is a LIMIT error after which
 * the pipeline renders on; the colour image renders and
 * shows the fluid where the screen-space path does; and a new upload gives a
 * new mesh (the cache follows the frame). */
#include <math.h>
#include <stdio.h>

#include "render_fixture.h"
#include "test_util.h"

#define RADIUS 0.5
#define SIZE 96u
/* The mesh's facets at 0.3 radii cells (up to 0.5 radii across: 3% sagitta)
 * and the metaball field's linear interpolation along edges (vertices within
 * about 4% of the sphere: at one radius the field of reach 3 radii curves half
 * as fast as it falls, where that of reach 2 curved a third as fast) keep its
 * depth within this of the sphere's, in radii, where the sphere faces the
 * camera (its depth grows steeply towards the silhouette, which facets cut:
 * there only the coverage is compared). */
#define DEPTH_TOLERANCE_RADII 0.08
#define FACING 0.25
/* Pixels this close to the silhouette (relative to r^2) may go either way. */
#define EDGE_SLACK 0.05

static fc_settings mesh_settings(void)
{
    fc_settings s = test_settings((float)RADIUS, FC_SMOOTHING_NONE, 0);
    s.surface = FC_SURFACE_MODE_MESH;
    s.surface_cell = 0.3f;
    s.surface_smoothing = 0;
    return s;
}

static void check_sphere_depth(render_fixture *f, const double centre[3])
{
    float position[3] = {(float)centre[0], (float)centre[1], (float)centre[2]};
    fc_camera cam = axis_camera(3.0, SIZE, SIZE);
    fc_settings s = mesh_settings();
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, position, 1, &cam, &s, FC_AOV_DEPTH, 0, &depth), FC_OK);
    if (!depth.pixels)
        return;
    double worst = 0.0;
    uint32_t inside = 0, wrong_outside = 0;
    for (uint32_t row = 0; row < SIZE; row++)
        for (uint32_t x = 0; x < SIZE; x++) {
            double edge;
            double expected = analytic_sphere_depth(&cam, centre, RADIUS, x, row, &edge);
            float got = pixel_f32(&depth, x, row);
            if (fabs(edge) < EDGE_SLACK)
                continue;
            if (expected > 0.0) {
                inside++;
                if (got == 0.0f || edge > FACING)
                    worst = fmax(worst, got > 0.0f ? fabs(got - expected) / RADIUS : 1.0);
            } else {
                wrong_outside += got != 0.0f;
            }
        }
    CHECK_MSG(inside > 500 && worst < DEPTH_TOLERANCE_RADII && wrong_outside == 0,
              "centre (%g %g %g): %u pixels on the sphere, depth off by up to %.4f radii; %u pixels off it with depth",
              centre[0], centre[1], centre[2], inside, worst, wrong_outside);
    printf("sphere at (%g %g %g): %u pixels, depth within %.5f radii\n", centre[0], centre[1], centre[2], inside,
           worst);
    fc_image_free(&depth);
}

/* The thickness image is the mesh's chord: 2 sqrt(r^2 - b^2) for a ray
 * passing b from the centre, up to the facets and the difference between a
 * view ray's length and its depth span (under 1.5% at this image's corners). */
static void check_thickness(render_fixture *f)
{
    double centre[3] = {0, 0, 0};
    float position[3] = {0, 0, 0};
    fc_camera cam = axis_camera(3.0, SIZE, SIZE);
    fc_settings s = mesh_settings();
    fc_image thickness = {0};
    CHECK_CODE(render_positions(f, position, 1, &cam, &s, FC_AOV_THICKNESS, 0, &thickness), FC_OK);
    if (!thickness.pixels)
        return;
    double worst = 0.0;
    uint32_t counted = 0;
    for (uint32_t row = 0; row < SIZE; row++)
        for (uint32_t x = 0; x < SIZE; x++) {
            double edge;
            double depth = analytic_sphere_depth(&cam, centre, RADIUS, x, row, &edge);
            if (!(depth > 0.0) || edge < FACING)
                continue;
            counted++;
            worst = fmax(worst, fabs(pixel_f32(&thickness, x, row) - 2.0 * RADIUS * sqrt(edge)) / RADIUS);
        }
    CHECK_MSG(counted > 500 && worst < 2.0 * DEPTH_TOLERANCE_RADII, "%u pixels, thickness off by up to %.4f radii",
              counted, worst);
    printf("thickness: %u pixels within %.5f radii of the chord\n", counted, worst);
    fc_image_free(&thickness);
}

/* The colour image renders through the whole pipeline (thickness, shading,
 * floor, shadow) and covers the fluid where the screen path's does. */
static void check_colour(render_fixture *f)
{
    float position[3] = {0, 0, 0};
    fc_camera cam = axis_camera(3.0, SIZE, SIZE);
    fc_settings mesh = mesh_settings(), screen = test_settings((float)RADIUS, FC_SMOOTHING_NONE, 0);
    fc_image a = {0}, b = {0};
    CHECK_CODE(render_positions(f, position, 1, &cam, &mesh, FC_AOV_COLOR, 0, &a), FC_OK);
    CHECK_CODE(render_positions(f, position, 1, &cam, &screen, FC_AOV_COLOR, 0, &b), FC_OK);
    if (a.pixels && b.pixels) {
        const float *pa = a.pixels, *pb = b.pixels;
        /* The image's centre is fluid in both: the same shading of nearly the same surface. */
        size_t c = 4 * ((size_t)(SIZE / 2) * SIZE + SIZE / 2);
        double diff = 0.0;
        for (int k = 0; k < 3; k++)
            diff = fmax(diff, fabs(pa[c + k] - pb[c + k]));
        CHECK_MSG(diff < 0.05, "centre colour differs by %.4f between mesh and screen", diff);
    }
    fc_image_free(&a);
    fc_image_free(&b);
}

/* A frame whose grid passes the budget fails its --surface mesh render with
 * LIMIT, and the pipeline renders the next frame as before. */
static void check_limit(render_fixture *f)
{
    enum { SIDE = 40 };
    static float sparse[3 * SIDE * SIDE * SIDE];
    for (int k = 0, n = 0; k < SIDE; k++)
        for (int j = 0; j < SIDE; j++)
            for (int i = 0; i < SIDE; i++, n++) {
                sparse[3 * n] = i * 20.0f * (float)RADIUS;
                sparse[3 * n + 1] = j * 20.0f * (float)RADIUS;
                sparse[3 * n + 2] = k * 20.0f * (float)RADIUS;
            }
    fc_frame frame = {.count = SIDE * SIDE * SIDE, .positions = sparse};
    fc_camera cam = axis_camera(3.0, SIZE, SIZE);
    fc_settings s = mesh_settings();
    s.surface_cell = 1.0f;
    fc_image img = {0};
    fc_error err;
    CHECK_CODE(fc_pipeline_upload(f->pipeline, &frame, NULL, &err), FC_OK);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &s, FC_AOV_DEPTH, 0, &img, NULL, &err), FC_ERR_LIMIT);
    printf("sparse droplets: %s\n", err.message);
    fc_image_free(&img);
    check_sphere_depth(f, (double[3]){0, 0, 0});
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    check_sphere_depth(&f, (double[3]){0, 0, 0});
    check_sphere_depth(&f, (double[3]){0.4, -0.3, 0.2});   /* a new upload: a new mesh */
    check_thickness(&f);
    check_colour(&f);
    check_limit(&f);
    fixture_close(&f);
    return test_result();
}
