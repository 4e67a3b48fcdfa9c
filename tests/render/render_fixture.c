/* render_fixture.c — shared set-up and analytic references of the render tests. */
#include "render_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline_internal.h"
#include "readback.h"

static const double PI = 3.14159265358979323846;

bool fixture_gpu_choice(fc_gpu_choice *choice)
{
    const char *wanted = getenv("FC_TEST_GPU");
    *choice = (fc_gpu_choice){FC_GPU_SOFTWARE, 0};
    if (!wanted || !*wanted)
        return true;
    fc_error err = {0};
    if (fc_gpu_choice_parse(wanted, choice, &err) != FC_OK) {
        fprintf(stderr, "FC_TEST_GPU=%s: %s\n", wanted, err.message);
        return false;
    }
    return true;
}

bool fixture_open(render_fixture *f)
{
    *f = (render_fixture){0};
    fc_gpu_choice gpu;
    fc_error err = {0};
    if (!fixture_gpu_choice(&gpu))
        return false;
    if (fc_gl_context_create(&gpu, &f->gl, &err) != FC_OK) {
        fprintf(stderr, "no GL context: %s\n", err.message);
        return false;
    }
    if (fc_pipeline_create(NULL, &f->pipeline, &err) != FC_OK) {
        fprintf(stderr, "no pipeline: %s\n", err.message);
        fixture_close(f);
        return false;
    }
    return true;
}

bool fixture_open_splat(render_fixture *f, int argc, char **argv)
{
    fc_splat_method method = FC_SPLAT_AUTO;
    if (argc > 1 && strcmp(argv[1], "fragment") == 0)
        method = FC_SPLAT_FRAGMENT;
    else if (argc > 1 && strcmp(argv[1], "compute") == 0)
        method = FC_SPLAT_COMPUTE;
    else if (argc > 1) {
        fprintf(stderr, "usage: %s [fragment|compute]\n", argv[0]);
        return false;
    }
    if (!fixture_open(f))
        return false;
    fc_pipeline_force_splat(f->pipeline, method);
    f->splat = method;
    return true;
}

bool fixture_splat_as_forced(const render_fixture *f)
{
    return f->splat == FC_SPLAT_AUTO || fc_pipeline_last_splat(f->pipeline) == f->splat;
}

void fixture_close(render_fixture *f)
{
    fc_pipeline_destroy(f->pipeline);
    fc_gl_context_destroy(f->gl);
    *f = (render_fixture){0};
}

fc_camera axis_camera(double distance, uint32_t width, uint32_t height)
{
    return (fc_camera){
        .eye = {0.0f, 0.0f, (float)distance},
        .target = {0.0f, 0.0f, 0.0f},
        .up = {0.0f, 1.0f, 0.0f},
        .fov_y_deg = 40.0f,
        .width = width,
        .height = height,
    };
}

fc_settings test_settings(float radius, fc_smoothing smoothing, uint32_t iterations)
{
    return (fc_settings){
        .radius = radius,
        .smoothing = smoothing,
        .iterations = iterations,
        .fluid_color = {0.1f, 0.4f, 0.6f},
        .absorption = {1.0f, 0.5f, 0.25f},
        .ior = 1.33f,
        /* Full resolution and no optional effect, in values validation accepts. */
        .smooth_scale = 1.0f,
        .thickness_scale = 1.0f,
        .shininess = 1.0f,
        .foam_tau = 1.0f,
        .surface_cell = 1.0f,
    };
}

fc_code render_positions(render_fixture *f, const float *positions, uint64_t count, const fc_camera *cam,
                         const fc_settings *settings, fc_aov aov, int want_u8, fc_image *out)
{
    fc_frame frame = {.count = count, .positions = (float *)positions};
    fc_error err = {0};
    fc_code code = fc_pipeline_upload(f->pipeline, &frame, NULL, &err);
    if (code == FC_OK)
        code = fc_pipeline_render(f->pipeline, cam, settings, aov, want_u8, out, NULL, &err);
    if (code != FC_OK)
        fprintf(stderr, "render failed: %s\n", err.message);
    return code;
}

float pixel_f32(const fc_image *img, uint32_t x, uint32_t row)
{
    return ((const float *)img->pixels)[(size_t)row * img->width + x];
}

double image_sum(const fc_image *img)
{
    double sum = 0.0;
    for (uint32_t row = 0; row < img->height; row++)
        for (uint32_t x = 0; x < img->width; x++)
            sum += pixel_f32(img, x, row);
    return sum;
}

float *lattice_ball(int steps, float spacing, float lift, uint64_t *count)
{
    size_t side = 2 * (size_t)steps + 1;
    float *p = malloc(3 * sizeof(float) * side * side * side);
    uint64_t n = 0;
    for (int i = -steps; i <= steps && p; i++)
        for (int j = -steps; j <= steps; j++)
            for (int k = -steps; k <= steps; k++)
                if (i * i + j * j + k * k <= steps * steps) {
                    p[3 * n] = (float)i * spacing;
                    p[3 * n + 1] = (float)j * spacing;
                    p[3 * n + 2] = (float)k * spacing + lift;
                    n++;
                }
    *count = n;
    return p;
}

/* Focal lengths of the camera's projection, from its definition. */
static void focal_lengths(const fc_camera *cam, double *fx, double *fy)
{
    *fy = 1.0 / tan(cam->fov_y_deg * PI / 360.0);
    *fx = *fy * cam->height / cam->width;
}

double analytic_sphere_depth(const fc_camera *cam, const double centre[3], double radius, uint32_t x,
                             uint32_t row, double *edge)
{
    double fx, fy;
    focal_lengths(cam, &fx, &fy);
    double ndc_x = (x + 0.5) / cam->width * 2.0 - 1.0;
    double ndc_y = 1.0 - (row + 0.5) / cam->height * 2.0;
    /* View space of an axis camera is world space shifted by the eye. */
    double c[3] = {centre[0], centre[1], centre[2] - cam->eye[2]};
    double d[3] = {ndc_x / fx, ndc_y / fy, -1.0};
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double dc = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];
    double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    /* |t d - c|² = r²  <=>  dd t² - 2 dc t + cc - r² = 0 */
    double discriminant = dc * dc - dd * (cc - radius * radius);
    double miss_sq = cc - dc * dc / dd;   /* squared distance from the centre to the ray */
    *edge = (radius * radius - miss_sq) / (radius * radius);
    if (discriminant <= 0.0)
        return 0.0;
    return (dc - sqrt(discriminant)) / dd;
}

void analytic_project(const fc_camera *cam, const double point[3], double *x, double *row)
{
    double fx, fy;
    focal_lengths(cam, &fx, &fy);
    double depth = cam->eye[2] - point[2];
    double ndc_x = fx * point[0] / depth;
    double ndc_y = fy * point[1] / depth;
    *x = (ndc_x + 1.0) * 0.5 * cam->width;
    *row = (1.0 - ndc_y) * 0.5 * cam->height;
}

fc_code read_target(const fc_render_target *target, uint32_t channels, fc_image *img, fc_error *err)
{
    fc_readback readback = fc_readback_init();
    fc_code code = fc_readback_run(&readback, target, channels, FC_PIXEL_F32, img, err);
    fc_readback_release(&readback);
    return code;
}
