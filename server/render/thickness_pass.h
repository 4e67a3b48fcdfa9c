/* thickness_pass.h — fluid thickness (van der Laan et al. 2009, §3.3): the
 * summed length of the view ray inside every sphere, in world units. */
#ifndef FC_THICKNESS_PASS_H
#define FC_THICKNESS_PASS_H

#include "render_target.h"
#include "sphere_sprites.h"

typedef struct fc_thickness_pass {
    fc_sphere_sprites sprites;
    fc_render_target target;   /* R32F thickness */
} fc_thickness_pass;

fc_code fc_thickness_pass_create(const char *shader_dir, fc_thickness_pass *pass, fc_error *err);
void fc_thickness_pass_destroy(fc_thickness_pass *pass);

/* Accumulates the particles' thickness into pass->target, sized to the view.
 * No depth test: there is no scene geometry that could hide fluid yet. */
fc_code fc_thickness_pass_run(fc_thickness_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                              float radius, fc_error *err);

#endif
