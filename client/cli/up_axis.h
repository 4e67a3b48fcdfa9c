/* up_axis.h — guessing which signed axis is "up" (against gravity) from the
 * particles alone, so auto-framed pictures of y-up data come out upright.
 *
 * Fluid rests on a floor: the extreme layer on the floor side is flat and
 * densely populated (the whole footprint touches it), while the opposite end
 * is a free surface that thins out into crests, jets and spray. Walls give
 * flat dense layers too, but on both ends of their axis alike, or, where the
 * fluid leans on one wall, a smaller one than the floor. So for each axis the
 * guess counts the particles within a slab about 1.5 particle spacings thick
 * at each end, and calls the axis whose ends differ most (weighted by the size
 * of the dense end, below) the gravity axis, its dense end down. A box, a ball
 * or a uniform cloud shows no such difference: then the guess is the +z
 * default and says so. */
#ifndef FC_UP_AXIS_H
#define FC_UP_AXIS_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"

/* At most this many particles (a deterministic spread-out sample) are looked
 * at, which keeps a 1M-particle frame to a few milliseconds. */
#define FC_UP_SAMPLE_MAX 16384

/* A dense end only counts as a floor when it spans the fluid: its slab's
 * extent along each of the two other axes is at least this fraction of the
 * fluid's (fluid rests on its floor across its whole width; the flat facet of
 * a lattice ball or the tip of a crest does not). */
#define FC_UP_MIN_SPAN 0.5f
/* Each axis whose dense end is a floor scores its contrast (below) times the
 * size of that end relative to the largest dense end of the three: fluid
 * spreads under gravity, so its floor is a larger contact than the part of a
 * wall it leans on. The best-scoring axis is the gravity axis when its sparse
 * end holds at most half as many particles as its dense end (contrast >=
 * 0.5)... */
#define FC_UP_MIN_CONTRAST 0.5f
/* ...and the dense end holds at least this many sampled particles (a floor is
 * a populated layer, not a handful of points). */
#define FC_UP_MIN_FLOOR 16u
/* Scores within this much of the best count as a tie, won by z, then y (the
 * common conventions). */
#define FC_UP_TIE 0.1f

typedef struct fc_up_guess {
    int axis;              /* 0 = x, 1 = y, 2 = z */
    int sign;              /* +1 or -1: up is sign * unit vector of axis */
    bool from_particles;   /* false: nothing stood out; axis/sign are the +z default */
    /* Per axis: (low-end count - high-end count) / the larger of the two, in
     * [-1, 1]; positive when the low end is the dense one (up = +axis). 0 for
     * an axis too thin to have two separate end slabs. */
    float contrast[3];
    uint32_t end_count[3][2];   /* sampled particles in the [low, high] end slab of each axis */
    /* The smaller of the end slab's two extents across the axis, relative to
     * the fluid's extents there (see FC_UP_MIN_SPAN). */
    float end_span[3][2];
    float slab;                 /* thickness of the end slabs, world units */
    uint64_t sampled;           /* particles looked at */
} fc_up_guess;

/* Guesses the up axis of the frame's particles (positions must be finite:
 * fc_frame_validate). Any count works: an empty or tiny frame gets the
 * default. FC_ERR_NOMEM when the sample cannot be allocated. */
fc_code fc_up_axis_guess(const fc_frame *frame, fc_up_guess *out, fc_error *err);

/* The unit vector of the guess. */
void fc_up_axis_vector(const fc_up_guess *guess, float up[3]);

/* "+x", "-x", ... "-z" for axis 0..2 and sign +-1. */
const char *fc_up_axis_name(int axis, int sign);

#endif
