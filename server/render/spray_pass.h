/* spray_pass.h — the spray (spray_classes.h: isolated particles, or those
 * below the density threshold), drawn as small clear droplets of varied size
 * over the composited image (spray.frag.glsl), depth-tested against the
 * fluid and the floor, and whitened by speed when settings.foam asks for it
 * (Cords & Staadt, Instant Liquids, §4).
 *
 * When the frame has velocities, each droplet is a streak along its velocity
 * as the camera sees it (the velocity's component across the view): a drop
 * seen during part of a frame's exposure. Its length grows with its speed
 * relative to the frame's mean speed, up to FC_SPRAY_MAX_STREAK times its
 * width, so no data set's units or frame rate need tuning and no streak
 * crosses the image; without velocities every droplet is round. */
#ifndef FC_SPRAY_PASS_H
#define FC_SPRAY_PASS_H

#include <stdint.h>

#include "environment.h"
#include "fc_frame.h"
#include "particle_attributes.h"
#include "render_target.h"
#include "sphere_sprites.h"

/* The longest streak, in droplet widths: a droplet moving across the view
 * far faster than the flow around it. */
#define FC_SPRAY_MAX_STREAK 3.0f

typedef struct fc_spray_pass {
    fc_sphere_sprites sprites;
    GLuint velocities;          /* vec4 per spray droplet (world velocity), from the first spray slot on */
    uint64_t velocity_capacity; /* droplets the buffer holds */
} fc_spray_pass;

fc_code fc_spray_pass_create(const char *shader_dir, fc_spray_pass *pass, fc_error *err);
void fc_spray_pass_destroy(fc_spray_pass *pass);

/* Blends the particles from draw slot `first` to the end over `target`, whose
 * depth buffer holds the scene's depth (the composite writes it). `frame` is
 * the uploaded frame (attributes' draw order maps slots to its particles):
 * its velocities, when it has them, stretch the droplets. */
fc_code fc_spray_pass_run(fc_spray_pass *pass, const fc_particle_buffer *particles, uint64_t first,
                          const fc_particle_attributes *attributes, const fc_frame *frame, const fc_view *view,
                          const fc_environment *env, const fc_settings *settings, const fc_render_target *target,
                          fc_error *err);

#endif
