/* shadow_pass.h — the fluid's shadow on the built-in floor: the thickness of
 * fluid along the sun's rays, splatted from the sun by the thickness pass
 * into a square map, through which environment.frag.glsl attenuates the
 * sunlight on each floor point (Beer-Lambert), so that a splash is seen to
 * stand above the floor. */
#ifndef FC_SHADOW_PASS_H
#define FC_SHADOW_PASS_H

#include "depth_pass.h"
#include "environment.h"
#include "gpu_memory.h"
#include "pass_profile.h"
#include "thickness_pass.h"

typedef struct fc_shadow_pass {
    /* Their own targets. The depth pass splats the thickness at half the
     * map's resolution (through its compute splat where sprites are small,
     * as they are in the map: several times cheaper per particle on a CPU
     * rasterizer), unless the camera's depth pass splatted it into
     * splat.thickness already (fc_shadow_pass_thickness); and the depth,
     * where meshes need it, at the map's; the thickness pass blurs the
     * thickness. */
    fc_depth_pass splat;
    fc_thickness_pass blur;
    /* The blurred map boxed once more for the floor's one tap (shadow_box.frag.glsl). */
    fc_render_target box;
    GLuint box_program;
    GLuint empty_vertex_array;
    fc_view sun_view;   /* the sun's camera of the last run: the meshes' shadows are cast through it */
} fc_shadow_pass;

fc_code fc_shadow_pass_create(const char *shader_dir, fc_shadow_pass *pass, fc_error *err);
void fc_shadow_pass_destroy(fc_shadow_pass *pass);

/* Splats the particles (inside the box [lo, hi], of the settings' radius;
 * the box may hold meshes too, which the sun's view then frames as well)
 * as seen from env->sun and sets env's shadow: the map, the world-to-map
 * transform, the extinction per world unit of thickness and, `with_depth`,
 * the fluid's nearest depth from the sun (which meshes in front of the fluid
 * compare; nothing else reads it, and without it the splat leaves out the
 * depth, its pinhole fill and its resolve: env->fluid_sun_depth is 0). */
fc_code fc_shadow_pass_run(fc_shadow_pass *pass, const fc_particle_buffer *particles, const float lo[3],
                           const float hi[3], const fc_settings *settings, bool with_depth, bool splatted,
                           fc_pass_profile *profile, fc_environment *env, fc_error *err);

/* The view fc_shadow_pass_run splats the map's thickness in (the sun's
 * camera at a reduced resolution) for these arguments, and the target it
 * splats it into: with `splatted`, fc_shadow_pass_run takes the thickness
 * as splatted there already at that view's size (the camera's depth pass
 * does so in its own walk of the particles, fc_depth_pass_run_fused). */
fc_view fc_shadow_pass_thickness_view(const fc_particle_buffer *particles, const float lo[3], const float hi[3],
                                      const fc_settings *settings, const fc_environment *env);
fc_render_target *fc_shadow_pass_thickness(fc_shadow_pass *pass);

void fc_shadow_pass_tally(const fc_shadow_pass *pass, fc_gpu_memory *m);
void fc_shadow_pass_trim(fc_shadow_pass *pass);

#endif
