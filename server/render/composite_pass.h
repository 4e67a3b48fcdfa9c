/* composite_pass.h — shading (van der Laan et al. 2009, §3.5, eqs. 13-15):
 * smoothed depth, thickness, noise and background become the final colour,
 * and the fluid's depth the depth buffer's content. The background pass has
 * filled the target where there is no fluid (fc_composite_pass_target). */
#ifndef FC_COMPOSITE_PASS_H
#define FC_COMPOSITE_PASS_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "environment.h"
#include "render_target.h"
#include "shader_variants.h"

typedef struct fc_composite_pass {
    GLuint mask_program;    /* stencil and depth on fluid pixels (fluid_mask.frag.glsl) */
    fc_program_variants programs;   /* the fluid's shading, on the stencil (composite.frag.glsl), by the
                                       features a render uses (shader_variants.h) */
    GLuint empty_vertex_array;
    GLuint depth_sampler;   /* nearest, for the fluid's depth (fluid_pixel.frag.glsl) */
    fc_render_target srgb_target;    /* GL_SRGB8_ALPHA8: display-ready 8-bit output, with depth */
    fc_render_target float_target;   /* GL_RGBA32F: linear output, with depth */
} fc_composite_pass;

/* The textures the composite reads, each from an earlier pass. */
typedef struct fc_composite_inputs {
    const fc_render_target *surface_depth;   /* smoothed linear depth */
    const fc_render_target *thickness;       /* any resolution: sampled bilinearly */
    const fc_render_target *background;
    const fc_render_target *noise;           /* N(x, y) of the noise pass; NULL: no noise (nor foam) */
    GLuint environment_map;                  /* cube map reflected in the fluid; 0 = the built-in scene */
    bool colored;                            /* the thickness carries the fluid's colour (thickness_pass.h) */
    bool depth_tested;                       /* opaque meshes lie in the depth buffer: fluid behind them stays
                                                hidden (else the fluid's depth is written wherever it is) */
    bool masked;                             /* the background pass laid down the mask already: the stencil
                                                and the fluid's depth (fc_background_pass_run), not depth_tested */
} fc_composite_inputs;

/* flat_constants: the shading programs take their uniforms as flat inputs (flat_constants.h). */
fc_code fc_composite_pass_create(const char *shader_dir, bool flat_constants, fc_composite_pass *pass,
                                 fc_error *err);
void fc_composite_pass_destroy(fc_composite_pass *pass);

/* The target the next run with want_u8 draws into, the sRGB target or the
 * float one, sized to the view: the background pass draws it first. */
fc_code fc_composite_pass_target(fc_composite_pass *pass, const fc_view *view, bool want_u8,
                                 const fc_render_target **target, fc_error *err);

/* Shades the fluid over the background in the target of
 * fc_composite_pass_target, writing the fluid's depth into its depth buffer
 * (the background pass wrote the floor's, else the far plane's, elsewhere);
 * sets *result to it. */
fc_code fc_composite_pass_run(fc_composite_pass *pass, const fc_composite_inputs *in, const fc_view *view,
                              const fc_environment *env, const fc_settings *settings, bool want_u8,
                              const fc_render_target **result, fc_error *err);

#endif
