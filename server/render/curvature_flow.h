/* curvature_flow.h — screen-space curvature flow (van der Laan et al. 2009,
 * §3.2): iterated explicit Euler steps that move linear depth along the mean
 * curvature, flattening the bumps between particles but not the silhouettes. */
#ifndef FC_CURVATURE_FLOW_H
#define FC_CURVATURE_FLOW_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "render_target.h"

typedef struct fc_curvature_flow {
    GLuint program;                  /* a compute shader writing image unit 0 */
    GLint group_size[3];             /* its workgroup's invocations */
    fc_render_target ping_pong[2];   /* R32F, sized to the input */
} fc_curvature_flow;

fc_code fc_curvature_flow_create(const char *shader_dir, fc_curvature_flow *cf, fc_error *err);
void fc_curvature_flow_destroy(fc_curvature_flow *cf);

/* Runs `iterations` steps on `depth` (R32F linear depth, 0 = background; left
 * unchanged) and sets *result to the target holding the outcome (`depth`
 * itself for 0 iterations). pixel_scale is (Cx, Cy), see fc_view_pixel_scale;
 * neighbours further apart in depth than depth_jump are separate surfaces. */
fc_code fc_curvature_flow_run(fc_curvature_flow *cf, const fc_render_target *depth, uint32_t iterations,
                              const float pixel_scale[2], float depth_jump, const fc_render_target **result,
                              fc_error *err);

#endif
