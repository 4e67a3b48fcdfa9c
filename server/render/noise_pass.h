/* noise_pass.h — the surface noise texture N(x, y) (van der Laan et al. 2009,
 * §3.4, eqs. 10-11): per-particle noise splats that move with the particles,
 * for the composite's normal perturbation and foam and the noise AOV. */
#ifndef FC_NOISE_PASS_H
#define FC_NOISE_PASS_H

#include "particle_attributes.h"
#include "render_target.h"
#include "sphere_sprites.h"

typedef struct fc_noise_pass {
    fc_sphere_sprites sprites;
    fc_render_target target;   /* R32F N(x, y) */
} fc_noise_pass;

fc_code fc_noise_pass_create(const char *shader_dir, fc_noise_pass *pass, fc_error *err);
void fc_noise_pass_destroy(fc_noise_pass *pass);

/* Sums the noise splats of the surface particles (each scaled by its record's
 * amplitude and by `amplitude`) over `surface_depth` into pass->target, sized
 * to the view. With amplitude <= 0 the target is all 0. */
fc_code fc_noise_pass_run(fc_noise_pass *pass, const fc_particle_buffer *surface,
                          const fc_particle_attributes *attributes, const fc_render_target *surface_depth,
                          const fc_view *view, float radius, float amplitude, fc_error *err);

#endif
