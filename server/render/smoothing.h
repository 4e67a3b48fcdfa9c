/* smoothing.h — the depth smoothing stage behind one small interface: every
 * method (curvature flow, bilateral, binomial, narrow-range), at full or
 * reduced resolution, without the pipeline knowing which. */
#ifndef FC_SMOOTHING_H
#define FC_SMOOTHING_H

#include <stdbool.h>
#include <stdint.h>

#include "binomial_filter.h"
#include "curvature_flow.h"
#include "resolution_scale.h"
#include "separable_filter.h"
#include "silhouette_blend.h"
#include "smoothing_params.h"

typedef struct fc_smoother {
    fc_curvature_flow curvature_flow;
    fc_separable_filter bilateral;
    fc_separable_filter narrow_range;
    fc_binomial_filter binomial;
    fc_resolution_scale resolution;
    fc_silhouette_blend silhouette_blend;
    /* Of the last run: the smoothed depth on the reduced grid and its block
     * size, or NULL when it ran at full resolution (or not at all). */
    const fc_render_target *low_resolution;
    uint32_t block;
    float depth_jump;
} fc_smoother;

fc_code fc_smoother_create(const char *shader_dir, fc_smoother *s, fc_error *err);
void fc_smoother_destroy(fc_smoother *s);

/* Smooths `depth` (R32F linear depth, 0 = background; left unchanged) at
 * params->smooth_scale of its resolution and sets *result to a target of the
 * same size whose red channel holds the smoothed depth: `depth` itself for
 * FC_SMOOTHING_NONE or no iterations.
 * FC_ERR_INVALID_VALUE for an unknown method. */
fc_code fc_smoother_run(fc_smoother *s, const fc_render_target *depth, const fc_smoothing_params *params,
                        const fc_render_target **result, fc_error *err);

/* After a run at reduced resolution, blends the shaded colour `shaded` (sRGB
 * 8-bit when want_u8, else float) over the silhouettes and sets *result to the
 * blended image; after a full-resolution run *result is `shaded` itself. */
fc_code fc_smoother_blend_silhouettes(fc_smoother *s, const fc_render_target *shaded, bool want_u8,
                                      const fc_render_target **result, fc_error *err);

/* Adds the targets of every method, the resolution change and the
 * silhouette blend to m. */
void fc_smoother_tally(const fc_smoother *s, fc_gpu_memory *m);

/* Frees every method's targets; the next run allocates those it uses again. */
void fc_smoother_trim(fc_smoother *s);

#endif
