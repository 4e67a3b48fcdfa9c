/* background_pass.h — the scene without fluid (the client's background image,
 * else the built-in sky and floor), rendered into its own texture first so the
 * composite pass can sample it at refracted positions (van der Laan et al.
 * 2009, S in eq. 14). The same draw fills the composite's target where there
 * is no fluid (colour and the floor's depth): one full-screen pass, not two. */
#ifndef FC_BACKGROUND_PASS_H
#define FC_BACKGROUND_PASS_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "environment.h"
#include "render_target.h"
#include "scene_textures.h"
#include "shader_variants.h"

typedef struct fc_background_pass {
    fc_program_variants programs;   /* by the features a render uses (shader_variants.h) */
    GLuint empty_vertex_array;
    GLuint depth_sampler;      /* nearest, for the fluid's depth (fluid_pixel.frag.glsl) */
    fc_render_target target;   /* RGBA16F linear radiance, bilinear so refraction samples smoothly */
    GLuint framebuffer;        /* target's colour and the composite target's colour and depth */
    bool writes_mask;          /* the driver has ARB_shader_stencil_export: the pass can lay down the mask */
} fc_background_pass;

/* flat_constants: the programs take their uniforms as flat inputs (flat_constants.h). */
fc_code fc_background_pass_create(const char *shader_dir, bool flat_constants, fc_background_pass *pass,
                                  fc_error *err);
void fc_background_pass_destroy(fc_background_pass *pass);

/* `scene` may be NULL (built-in scene); a background image is scaled to cover
 * the view, keeping its aspect ratio and cropping what overhangs evenly.
 * Draws into pass->target and into `composite` (a target with depth, at
 * least the view's size): the background colour, and the depth of the floor,
 * else of the far plane. With `fluid_depth` (the smoothed linear depth; only
 * where fc_background_pass_writes_mask, and not with opaque meshes, which the
 * mask must be tested against) it also does the composite's mask: the
 * fluid's depth and stencil 1 where the fluid is in front of the floor, 0
 * elsewhere (fc_composite_inputs.masked). */
fc_code fc_background_pass_run(fc_background_pass *pass, const fc_view *view, const fc_environment *env,
                               const fc_scene_textures *scene, const fc_render_target *fluid_depth,
                               const fc_render_target *composite, fc_error *err);

/* Whether the driver lets the pass lay down the composite's mask (ARB_shader_stencil_export). */
bool fc_background_pass_writes_mask(const fc_background_pass *pass);

#endif
