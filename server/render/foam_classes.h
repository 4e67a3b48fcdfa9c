/* foam_classes.h — which particles are foam (Ihmsen et al. 2012, "Unified
 * spray, foam and air bubbles for particle-based fluids", §3-4): where the
 * flow traps air, neighbours move toward each other, and the trapped-air
 * potential
 *     I_ta(i) = sum_j |v_ij| (1 - v̂_ij · x̂_ij) W(|x_ij|),  W(d) = 1 - d/h,
 * over the neighbours j within h (x_ij = x_i - x_j, v_ij = v_i - v_j) grows.
 * A foam particle is a surface particle, not spray (spray_classes.h), with
 * fewer than FC_FOAM_MAX_NEIGHBOURS neighbours (no bulk particle deep in the
 * body), whose I_ta stands out of the frame's own spread: above the mean plus
 * 1.5 standard deviations of the candidates' I_ta, and above a tenth of the
 * frame's root-mean-square speed (so a near-calm frame's noise is no foam).
 * Both bounds are the frame's own, so the default needs no tuning in any
 * unit. I_ta depends on velocity differences only: water at rest or moving
 * as one body (a uniform velocity) has I_ta 0 everywhere and no foam, by
 * construction. A frame without velocities has no foam. Each foam
 * particle's count of foam neighbours (`company`) tells a patch from a lone
 * particle, for the foam pass (foam_pass.h).
 *
 * Walks the hashed grid fc_spray_classes_compute built (one support wide),
 * so it runs after it and only where it built one (spray_neighbours > 0, a
 * frame without per-particle radii); about one pass over the particles and
 * their neighbours within the support. Deterministic. */
#ifndef FC_FOAM_CLASSES_H
#define FC_FOAM_CLASSES_H

#include <stdint.h>

#include "fc_frame.h"
#include "fluidcast_types.h"
#include "spray_classes.h"

/* A particle with this many neighbours within the support (2.2 spacings) or
 * more is inside the body: a cubic lattice's inner particle has 32 there, one
 * on a flat face 22, so 28 keeps faces, edges and loose clusters. */
#define FC_FOAM_MAX_NEIGHBOURS 28u

typedef struct fc_foam_classes {
    uint8_t *foam;       /* per particle, frame order: 1 foam, 0 not */
    float *potential;    /* per particle: I_ta (world units per frame); 0 for spray and bulk */
    uint8_t *company;    /* per foam particle: how many of its neighbours are foam too (at most 255); 0 else */
    float *gathered;     /* scratch: positions and velocities in the grid's slot order, 6 floats a slot */
    uint64_t capacity;
    uint64_t count;      /* foam particles of the last frame */
    float threshold;     /* the I_ta a foam particle passed in the last frame; 0: none was found */
} fc_foam_classes;

/* Fills f->foam for `frame` from the grid and spray keys of `spray`, which
 * fc_spray_classes_compute filled for the same frame. FC_ERR_NOMEM when the
 * arrays cannot grow. */
fc_code fc_foam_classes_compute(fc_foam_classes *f, const fc_spray_classes *spray, const fc_frame *frame,
                                fc_error *err);

void fc_foam_classes_free(fc_foam_classes *f);

#endif
