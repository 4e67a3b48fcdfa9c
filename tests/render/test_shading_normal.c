/* test_shading_normal.c — the normal AOV: three float channels holding the
 * view-space unit normal of the surface, 0 where there is no fluid; on a
 * sphere it matches the analytic normal, pointing at the camera at the
 * centre; surface noise tilts it but keeps it a unit vector. */
#include <math.h>

#include "shading_fixture.h"
#include "test_util.h"

#define SIZE 65   /* odd: pixel 32 sits on the view axis */
#define RADIUS 0.5
#define DISTANCE 4.0

static fc_code render_sphere_normals(render_fixture *f, float noise, fc_image *out)
{
    const float origin[3] = {0.0f, 0.0f, 0.0f};
    fc_frame frame = {.count = 1, .positions = (float *)origin};
    fc_camera cam = axis_camera(DISTANCE, SIZE, SIZE);
    fc_settings settings = test_settings((float)RADIUS, FC_SMOOTHING_NONE, 0);
    settings.noise = noise;
    return render_frame(f, &frame, &cam, &settings, NULL, FC_AOV_NORMAL, 0, out);
}

/* The sphere's unit normal where the ray through (x, row) hits it; view
 * space of an axis camera is world space shifted by the eye. */
static void analytic_normal(uint32_t x, uint32_t row, double n[3])
{
    fc_camera cam = axis_camera(DISTANCE, SIZE, SIZE);
    const double centre[3] = {0.0, 0.0, 0.0};
    double edge, fy = 1.0 / tan(cam.fov_y_deg * 3.14159265358979323846 / 360.0);
    double depth = analytic_sphere_depth(&cam, centre, RADIUS, x, row, &edge);
    double ndc[2] = {(x + 0.5) / SIZE * 2.0 - 1.0, 1.0 - (row + 0.5) / SIZE * 2.0};
    double hit[3] = {ndc[0] / fy * depth, ndc[1] / fy * depth, -depth};
    const double centre_view[3] = {0.0, 0.0, -DISTANCE};
    for (int c = 0; c < 3; c++)
        n[c] = (hit[c] - centre_view[c]) / RADIUS;
}

static double length3(const fc_image *img, uint32_t x, uint32_t row)
{
    double sum = 0.0;
    for (uint32_t c = 0; c < 3; c++)
        sum += channel_f32(img, x, row, c) * channel_f32(img, x, row, c);
    return sqrt(sum);
}

static void test_sphere_normals(render_fixture *f)
{
    fc_image img = {0};
    CHECK_CODE(render_sphere_normals(f, 0.0f, &img), FC_OK);
    CHECK(img.channels == 3 && img.type == FC_PIXEL_F32 && img.width == SIZE && img.height == SIZE);
    CHECK_NEAR(channel_f32(&img, 32, 32, 0), 0.0, 0.03);
    CHECK_NEAR(channel_f32(&img, 32, 32, 1), 0.0, 0.03);
    CHECK_NEAR(channel_f32(&img, 32, 32, 2), 1.0, 1e-3);
    for (uint32_t c = 0; c < 3; c++)
        CHECK(channel_f32(&img, 0, 0, c) == 0.0f);
    /* Up and to the right of the centre, inside the silhouette: rows run top
     * to bottom, so the normal's y is positive above the centre. */
    const uint32_t probes[][2] = {{40, 32}, {32, 24}, {38, 27}, {26, 38}};
    for (size_t i = 0; i < sizeof probes / sizeof probes[0]; i++) {
        double n[3];
        analytic_normal(probes[i][0], probes[i][1], n);
        for (uint32_t c = 0; c < 3; c++)
            CHECK_MSG(fabs(channel_f32(&img, probes[i][0], probes[i][1], c) - n[c]) < 0.05,
                      "pixel (%u, %u) component %u: %g, analytic %g", probes[i][0], probes[i][1], c,
                      channel_f32(&img, probes[i][0], probes[i][1], c), n[c]);
    }
    fc_image_free(&img);
}

static void test_noise_tilts_normals(render_fixture *f)
{
    fc_image smooth = {0}, rippled = {0};
    CHECK_CODE(render_sphere_normals(f, 0.0f, &smooth), FC_OK);
    CHECK_CODE(render_sphere_normals(f, 1.0f, &rippled), FC_OK);
    int tilted = 0, not_unit = 0;
    for (uint32_t row = 0; row < SIZE; row++)
        for (uint32_t x = 0; x < SIZE; x++) {
            if (length3(&smooth, x, row) == 0.0)
                continue;
            double dot = 0.0;
            for (uint32_t c = 0; c < 3; c++)
                dot += channel_f32(&smooth, x, row, c) * channel_f32(&rippled, x, row, c);
            tilted += dot < cos(2.0 * 3.14159265358979323846 / 180.0);
            not_unit += fabs(length3(&rippled, x, row) - 1.0) > 1e-4;
        }
    CHECK_MSG(tilted > 100, "only %d normals tilted by more than 2 degrees", tilted);
    CHECK(not_unit == 0);
    fc_image_free(&smooth);
    fc_image_free(&rippled);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_sphere_normals(&f);
    test_noise_tilts_normals(&f);
    fixture_close(&f);
    return test_result();
}
