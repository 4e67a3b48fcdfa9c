/* normal_pass.h — the normal AOV: the view-space shading normal of the fluid
 * surface (surface_normal.frag.glsl, as the composite computes it). */
#ifndef FC_NORMAL_PASS_H
#define FC_NORMAL_PASS_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "render_target.h"
#include "view.h"

typedef struct fc_normal_pass {
    GLuint program;
    GLuint empty_vertex_array;
    fc_render_target target;   /* RGBA32F: xyz = unit normal, 0 where there is no fluid */
} fc_normal_pass;

fc_code fc_normal_pass_create(const char *shader_dir, fc_normal_pass *pass, fc_error *err);
void fc_normal_pass_destroy(fc_normal_pass *pass);

/* Sets the inputs of surface_normal.frag.glsl on the program in use: the
 * smoothed depth, the noise texture (NULL: no noise, none is read) and the
 * particle radius; of the uniforms only those among the active locations
 * `uniforms` (fc_program_uniform_locations; FC_ALL_UNIFORMS: all). */
void fc_surface_normal_bind(const fc_render_target *surface_depth, const fc_render_target *noise, float radius,
                            uint64_t uniforms);

fc_code fc_normal_pass_run(fc_normal_pass *pass, const fc_render_target *surface_depth,
                           const fc_render_target *noise, const fc_view *view, float radius,
                           const fc_render_target **result, fc_error *err);

#endif
