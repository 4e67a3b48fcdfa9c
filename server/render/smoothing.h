/* smoothing.h — the depth smoothing stage behind one small interface, so other
 * filters (bilateral, narrow-range, reduced resolution, ...) can sit beside
 * curvature flow without the pipeline changing. */
#ifndef FC_SMOOTHING_H
#define FC_SMOOTHING_H

#include <stdint.h>

#include "curvature_flow.h"
#include "render_target.h"

typedef struct fc_smoothing_params {
    fc_smoothing method;
    uint32_t iterations;
    float pixel_scale[2];   /* (Cx, Cy), see fc_view_pixel_scale */
    float depth_jump;       /* world units: neighbours further apart in depth are separate surfaces */
} fc_smoothing_params;

typedef struct fc_smoother {
    fc_curvature_flow curvature_flow;
} fc_smoother;

fc_code fc_smoother_create(const char *shader_dir, fc_smoother *s, fc_error *err);
void fc_smoother_destroy(fc_smoother *s);

/* Smooths `depth` (R32F linear depth, 0 = background; left unchanged) and sets
 * *result to the target holding the smoothed depth: `depth` itself for
 * FC_SMOOTHING_NONE. FC_ERR_INVALID_VALUE for an unknown method. */
fc_code fc_smoother_run(fc_smoother *s, const fc_render_target *depth, const fc_smoothing_params *params,
                        const fc_render_target **result, fc_error *err);

#endif
