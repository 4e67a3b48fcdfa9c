/* mesh_pass.h — a client's meshes in the picture (PROTOCOL.md section 12):
 * their depth, which cuts the fluid where a mesh is nearer; the opaque ones
 * drawn into the scene before the fluid (into the background texture the
 * fluid refracts and into the image), the glass ones blended over the fluid
 * after it; and, seen from the sun, the opaque ones' shadows. Faces of a mesh
 * with hide_near whose front side faces the camera are culled in all of it,
 * so a tank's near walls neither show nor hide the fluid. */
#ifndef FC_MESH_PASS_H
#define FC_MESH_PASS_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "environment.h"
#include "gpu_memory.h"
#include "pipeline.h"
#include "render_target.h"
#include "view.h"

typedef struct fc_mesh_pass {
    GLuint depth_program;       /* linear depth of the nearest surface (mesh_depth.frag.glsl) */
    GLuint shade_program;       /* lit by the scene (mesh_shade.frag.glsl) */
    GLuint occlusion_program;   /* the fluid's depth cut (mesh_occlusion.comp.glsl) */
    GLuint shade_framebuffer;   /* background texture and image colour + depth, attached per run */
    fc_render_target depth;     /* R32F linear depth of the opaque meshes, 0 = none, with a depth buffer */
    fc_render_target sun_depth; /* R32F the same from the sun, +inf = none */
} fc_mesh_pass;

fc_code fc_mesh_pass_create(const char *shader_dir, fc_mesh_pass *pass, fc_error *err);
void fc_mesh_pass_destroy(fc_mesh_pass *pass);

/* Grows [lo, hi] to hold every mesh's bounds as placed. */
void fc_mesh_bounds(const fc_scene_mesh *meshes, uint32_t count, float lo[3], float hi[3]);

/* Whether any mesh is opaque (opacity 1): only those hide the fluid. */
bool fc_mesh_any_opaque(const fc_scene_mesh *meshes, uint32_t count);

/* Sets to 0 (no fluid) every pixel of `fluid_depth` (R32F linear depth, the
 * view's size) where an opaque mesh is nearer than the fluid. */
fc_code fc_mesh_pass_occlude(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count, const fc_view *view,
                             const fc_render_target *fluid_depth, fc_error *err);

/* Renders the opaque meshes (but those with hide_near) from the sun's view
 * of the fluid's shadow (env->has_shadow must be set) and gives env their
 * shadow: the floor and the meshes receive it. */
fc_code fc_mesh_pass_cast_shadows(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count,
                                  const fc_view *sun_view, fc_environment *env, fc_error *err);

/* Draws the opaque meshes into `background` (the RGBA16F scene radiance) and
 * `image` (the composite target, colour and depth), depth-tested against what
 * the background pass wrote. */
fc_code fc_mesh_pass_draw_opaque(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count,
                                 const fc_view *view, const fc_environment *env, const fc_render_target *background,
                                 const fc_render_target *image, bool want_u8, fc_error *err);

/* Blends the glass meshes over `image` with their opacity, depth-tested
 * against its depth (fluid, opaque meshes, floor), their far faces first. */
fc_code fc_mesh_pass_draw_glass(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count, const fc_view *view,
                                const fc_environment *env, const fc_render_target *image, bool want_u8,
                                fc_error *err);

void fc_mesh_pass_tally(const fc_mesh_pass *pass, fc_gpu_memory *m);
void fc_mesh_pass_trim(fc_mesh_pass *pass);

#endif
