/* render_fixture.h — what the render tests share: a software GL context with
 * a pipeline, an on-axis camera, and analytic sphere projection computed
 * independently of the pipeline's own camera code (double precision). */
#ifndef FC_RENDER_FIXTURE_H
#define FC_RENDER_FIXTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "egl_context.h"
#include "fluidcast_types.h"
#include "image.h"
#include "depth_pass.h"
#include "pipeline.h"
#include "render_target.h"

typedef struct render_fixture {
    fc_gl_context *gl;
    fc_pipeline *pipeline;
    fc_splat_method splat;   /* forced on the pipeline; FC_SPLAT_AUTO: not forced */
} render_fixture;

/* The device the render tests run on: FC_TEST_GPU (auto, software or an EGL
 * device index, as fluidcastd --gpu takes) or, unset, Mesa's llvmpipe, which
 * every machine has. bench/gpu_check.sh sets it to run the suite on a GPU.
 * False (with the reason on stderr) for a value fc_gpu_choice_parse refuses. */
bool fixture_gpu_choice(fc_gpu_choice *choice);

/* A context on fixture_gpu_choice's device (llvmpipe unless FC_TEST_GPU says
 * otherwise) and a pipeline with built-in shaders; false, after printing why,
 * when either fails. */
bool fixture_open(render_fixture *f);
void fixture_close(render_fixture *f);

/* fixture_open, then the surface splat the test's argument names forced on
 * the pipeline: "fragment" or "compute" (depth_pass.h); none leaves the
 * choice by sprite size. False, after printing why, for another argument. */
bool fixture_open_splat(render_fixture *f, int argc, char **argv);

/* Whether the last render splatted the way the fixture forced (a test that
 * should cover the compute splat must not silently test the other). */
bool fixture_splat_as_forced(const render_fixture *f);

/* Eye at (0, 0, distance) looking at the origin, up +y, 40 degree vertical fov. */
fc_camera axis_camera(double distance, uint32_t width, uint32_t height);

/* Plain settings: the given radius and smoothing, neutral material. */
fc_settings test_settings(float radius, fc_smoothing smoothing, uint32_t iterations);

/* Uploads `count` particles (xyz interleaved) and renders one image. */
fc_code render_positions(render_fixture *f, const float *positions, uint64_t count, const fc_camera *cam,
                         const fc_settings *settings, fc_aov aov, int want_u8, fc_image *out);

/* Value of a one-channel float image at column x, row (0 = top). */
float pixel_f32(const fc_image *img, uint32_t x, uint32_t row);

/* The sum of a one-channel float image's values. */
double image_sum(const fc_image *img);

/* The points of a cubic lattice of `spacing` within `steps` spacings of
 * (0, 0, lift): a solid ball of particles (xyz interleaved, malloc'd; NULL
 * when out of memory), their number in *count. */
float *lattice_ball(int steps, float spacing, float lift, uint64_t *count);

/* Reads a render target of a pass run on its own as `channels` floats into
 * img (rows top to bottom), through a readback made for the call. */
fc_code read_target(const fc_render_target *target, uint32_t channels, fc_image *img, fc_error *err);

/* The sphere seen through pixel (x, row) of an axis_camera image, solved
 * analytically. Returns the linear view depth of the front hit, or 0 on a
 * miss. *edge is how close the ray passes to the silhouette, as
 * (r² - miss distance²) / r²: near 0 the pixel could go either way. */
double analytic_sphere_depth(const fc_camera *cam, const double centre[3], double radius, uint32_t x,
                             uint32_t row, double *edge);

/* Pixel coordinates (x right, row down, continuous, pixel centres at +0.5)
 * where a world-space point projects in an axis_camera image. */
void analytic_project(const fc_camera *cam, const double point[3], double *x, double *row);

#endif
