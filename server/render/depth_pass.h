/* depth_pass.h — sphere depth splatting (van der Laan et al. 2009, §3.1):
 * linear view depth of the nearest sphere surface per pixel, 0 = no fluid. */
#ifndef FC_DEPTH_PASS_H
#define FC_DEPTH_PASS_H

#include "render_target.h"
#include "sphere_sprites.h"

typedef struct fc_depth_pass {
    fc_sphere_sprites sprites;
    fc_render_target target;   /* R32F linear depth + the depth buffer of the nearest-sphere test */
} fc_depth_pass;

fc_code fc_depth_pass_create(const char *shader_dir, fc_depth_pass *pass, fc_error *err);
void fc_depth_pass_destroy(fc_depth_pass *pass);

/* Renders the particles' depth into pass->target, sized to the view. */
fc_code fc_depth_pass_run(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                          float radius, fc_error *err);

#endif
