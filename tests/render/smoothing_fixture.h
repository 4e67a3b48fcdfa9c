/* smoothing_fixture.h — what the smoothing tests share: a software GL
 * context with a smoother, synthetic depth images uploaded into the real
 * passes, and measures of the result computed on the CPU. Images are W x H
 * floats in GL row order (y = 0 at the bottom), 0 = background. */
#ifndef FC_SMOOTHING_FIXTURE_H
#define FC_SMOOTHING_FIXTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "egl_context.h"
#include "smoothing.h"

#define SF_W 128
#define SF_H 96
#define SF_PIXELS (SF_W * SF_H)
/* A particle of SF_RADIUS at depth 5 spans about 2.6 pixels: kernels of a few pixels. */
#define SF_RADIUS 0.1f
#define SF_DEPTH_JUMP (4.0f * SF_RADIUS)

typedef struct smoothing_fixture {
    fc_gl_context *gl;
    fc_smoother smoother;
    fc_render_target input;
} smoothing_fixture;

/* false, after printing why, when the context or a shader fails. */
bool smoothing_open(smoothing_fixture *sf);
void smoothing_close(smoothing_fixture *sf);

/* Parameters for the test images: a 40 degree vertical field of view, the
 * fixture's particle radius and depth jump, fluid around depth 5. */
fc_smoothing_params smoothing_params(fc_smoothing method, uint32_t iterations, float smooth_scale);

/* Uploads `depth`, runs fc_smoother_run and reads the smoothed depth into `out`. */
fc_code smoothing_apply(smoothing_fixture *sf, const float *depth, const fc_smoothing_params *params, float *out);

/* Reads the red channel of a target (GL row order) into `out`. */
fc_code smoothing_read(const fc_render_target *target, float *out);

/* Method names as the tests' command lines spell them; -1 when unknown. */
int smoothing_method_by_name(const char *name);

/* Scenes. */
void scene_plane(float *depth, float z);
/* A plane at `z` with a Gaussian bump of `height` towards the camera in the middle. */
void scene_bump(float *depth, float z, float height, float sigma_px);
/* Adds a flat disc (camera-facing) at depth z, drawn over what is nearer-or-absent
 * only where it is nearer (as a depth test would). */
void scene_add_disc(float *depth, float cx, float cy, float radius_px, float z);

/* Sum of |discrete Laplacian| over pixels whose four neighbours are on the
 * same surface as they are (a curvature measure that ignores silhouettes). */
double total_curvature(const float *depth, float depth_jump);

/* Distance in pixels (chessboard metric, at most SF_FAR) from each pixel to
 * the nearest pixel that shows something else: background against fluid, or
 * another surface. */
#define SF_FAR 16
void silhouette_distance(const float *depth, uint8_t *distance);

#endif
