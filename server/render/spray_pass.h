/* spray_pass.h — the spray (spray_classes.h: isolated particles, or those
 * below the density threshold), drawn as small clear droplets of varied size
 * over the composited image (spray.frag.glsl), depth-tested against the
 * fluid and the floor, and whitened by speed when settings.foam asks for it
 * (Cords & Staadt, Instant Liquids, §4). */
#ifndef FC_SPRAY_PASS_H
#define FC_SPRAY_PASS_H

#include <stdint.h>

#include "environment.h"
#include "particle_attributes.h"
#include "render_target.h"
#include "sphere_sprites.h"

typedef struct fc_spray_pass {
    fc_sphere_sprites sprites;
} fc_spray_pass;

fc_code fc_spray_pass_create(const char *shader_dir, fc_spray_pass *pass, fc_error *err);
void fc_spray_pass_destroy(fc_spray_pass *pass);

/* Blends the particles from draw slot `first` to the end over `target`, whose
 * depth buffer holds the scene's depth (the composite writes it). */
fc_code fc_spray_pass_run(fc_spray_pass *pass, const fc_particle_buffer *particles, uint64_t first,
                          const fc_particle_attributes *attributes, const fc_view *view, const fc_environment *env,
                          const fc_settings *settings, const fc_render_target *target, fc_error *err);

#endif
