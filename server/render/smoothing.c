/* smoothing.c — dispatch of the depth smoothing methods. */
#include "smoothing.h"

#include "fc_error.h"

fc_code fc_smoother_create(const char *shader_dir, fc_smoother *s, fc_error *err)
{
    return fc_curvature_flow_create(shader_dir, &s->curvature_flow, err);
}

void fc_smoother_destroy(fc_smoother *s)
{
    fc_curvature_flow_destroy(&s->curvature_flow);
}

fc_code fc_smoother_run(fc_smoother *s, const fc_render_target *depth, const fc_smoothing_params *params,
                        const fc_render_target **result, fc_error *err)
{
    switch (params->method) {
    case FC_SMOOTHING_NONE:
        *result = depth;
        return FC_OK;
    case FC_SMOOTHING_CURVATURE:
        return fc_curvature_flow_run(&s->curvature_flow, depth, params->iterations, params->pixel_scale,
                                     params->depth_jump, result, err);
    }
    return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown smoothing method %d", (int)params->method);
}
