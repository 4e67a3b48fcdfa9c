/* foam_pass.h — the foam (foam_classes.h: surface particles where the flow
 * traps air, Ihmsen et al. 2012) drawn white and soft over the composited
 * surface (foam.frag.glsl): each foam particle a soft-edged disc of diffuse
 * white facing the camera, lit by the sun and the sky, of its own size (a
 * hash of its id, or of its index without ids, scaled with the particle
 * radius) and as opaque as its trapped-air potential stands above the
 * frame's threshold, up to settings.aerated_foam. The discs blend, so a
 * crowd of them is a white patch whose edge fades with the potential, and a
 * lone one a faint fleck: no bead, no haze. Each sprite sits in front of its
 * particle (a foam particle is at the surface, which the composite's depth
 * holds), so the fluid and the floor in front of it still hide it.
 *
 * Unlike settings.foam (foam_state.h: noise whitening driven by each
 * particle's velocity change across frames), this needs one frame with
 * velocities, and marks only where neighbours converge; nothing is drawn
 * for a frame without velocities, at rest or moving as one body. */
#ifndef FC_FOAM_PASS_H
#define FC_FOAM_PASS_H

#include <stdint.h>

#include "environment.h"
#include "fc_frame.h"
#include "foam_classes.h"
#include "particle_buffer.h"
#include "render_target.h"
#include "sphere_sprites.h"

typedef struct fc_foam_pass {
    fc_sphere_sprites sprites;
    fc_particle_buffer particles; /* the foam particles' positions, in the frame's order */
    GLuint looks;                 /* vec4 per foam particle: size factor, opacity */
    uint64_t look_capacity;       /* particles the looks buffer holds */
    uint64_t filled_generation;   /* the foam classes the buffers were filled from (the caller's count); 0: none */
    float filled_strength;        /* the strength they were filled with */
} fc_foam_pass;

fc_code fc_foam_pass_create(const char *shader_dir, fc_foam_pass *pass, fc_error *err);
void fc_foam_pass_destroy(fc_foam_pass *pass);

/* Fills the pass's buffers with the foam particles of `foam` (computed for
 * `frame`), unless already filled for `generation` (> 0: the caller counts
 * the foam classes it computed) and `strength`. */
fc_code fc_foam_pass_fill(fc_foam_pass *pass, const fc_foam_classes *foam, const fc_frame *frame, uint64_t generation,
                          float strength, fc_error *err);

/* Blends the filled foam over `target`, whose depth buffer holds the scene's
 * depth (the composite writes it); nothing when none was filled. */
fc_code fc_foam_pass_run(fc_foam_pass *pass, const fc_view *view, const fc_environment *env, float radius,
                         const fc_render_target *target, fc_error *err);

/* Empties the pass: the next run draws nothing until a fill. */
void fc_foam_pass_clear(fc_foam_pass *pass);

#endif
