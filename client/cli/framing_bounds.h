/* framing_bounds.h — the box the auto camera frames: the fluid, not its
 * farthest droplet.
 *
 * A frame's bounding box is stretched by whichever particle flew farthest:
 * one droplet of a splash flung to 15 times the pool's depth leaves the pool a
 * strip at the bottom of a picture of empty floor. What a user means by "the
 * fluid" is its bodies (a pool, a drop falling into it, a jet rising from
 * it), not the few droplets flung away from them. So, per axis, on a
 * deterministic sample of the particles:
 *
 *  - At most the outer FC_FRAMING_TAIL of the particles at each end can be
 *    left out: a separate body holding more than that (1 particle in 200) is
 *    always framed, however far away, since the 0.5th or 99.5th percentile
 *    lies in it. A falling drop holds a few percent of a scene; spray is
 *    sparser (the shared crown splash has at most 52 of its 51,517 particles,
 *    0.1%, above its tank's walls, most of them droplets of one particle). A smaller separate body is indistinguishable from spray by
 *    its count and may leave the picture: --eye/--target frame it on purpose.
 *  - And only beyond a gap: from that percentile the bound moves outwards over
 *    the sorted coordinates as long as no two neighbours are further apart
 *    than the larger of FC_FRAMING_GAP of the fluid's size and
 *    FC_FRAMING_GAP_SPACINGS particle spacings (a coarse fluid's outermost
 *    layer is a spacing from the next). A body of fluid is contiguous, so a
 *    compact fluid (a ball, a dam break, a pool with a jet rising from it)
 *    keeps its whole bounding box, and exactly the camera the full box gave;
 *    what is left out is separated from the rest by empty space.
 *
 * The cut on each side is a gap's width past the last sampled particle before
 * the gap, and the box is that of every particle (not only the sampled) inside
 * all six cuts, so its sides are particles' positions as the full box's are.
 * The work is a sort of at most FC_FRAMING_SAMPLE_MAX values per axis, the
 * sample's spacing (spread_sample.h) and one pass over the particles. */
#ifndef FC_FRAMING_BOUNDS_H
#define FC_FRAMING_BOUNDS_H

#include <stdint.h>

#include "fluidcast_types.h"

/* At most this many particles (spread_sample.h) choose the cuts. */
#define FC_FRAMING_SAMPLE_MAX 16384
/* The fraction of the particles at each end of each axis that may be left out. */
#define FC_FRAMING_TAIL 0.005
/* The gap that separates a left-out particle from the fluid: this fraction of
 * the largest extent of the box between the FC_FRAMING_TAIL percentiles... */
#define FC_FRAMING_GAP 0.05
/* ...or this many of the sample's particle spacings, whichever is larger.
 * Both are far above the distance between neighbouring sorted coordinates
 * inside a body (about its extent over the sample size) and far below the
 * distance of a droplet worth leaving out. */
#define FC_FRAMING_GAP_SPACINGS 2.0

typedef struct fc_framing_box {
    float lo[3], hi[3];   /* the box the auto camera frames */
    uint64_t left_out;    /* particles outside it: droplets far from the fluid */
    uint64_t sampled;     /* particles the cuts were chosen from */
} fc_framing_box;

/* The framing box of the frame's particles (positions finite:
 * fc_frame_validate); all zero for no particles. FC_ERR_NOMEM when the sample
 * cannot be allocated. */
fc_code fc_framing_box_of(const fc_frame *frame, fc_framing_box *out, fc_error *err);

/* Grows *into to hold `box` too (a sequence's camera frames the union of its
 * frames' boxes); its left_out and sampled become the larger of the two. */
void fc_framing_box_union(fc_framing_box *into, const fc_framing_box *box);

#endif
