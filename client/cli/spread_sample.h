/* spread_sample.h — the deterministic sample the CLI's particle statistics
 * (the up-axis guess, the framing box) look at instead of every particle of a
 * large frame, and the particle spacing measured on it. */
#ifndef FC_SPREAD_SAMPLE_H
#define FC_SPREAD_SAMPLE_H

#include <stdint.h>

#include "fluidcast_types.h"

/* The first m (<= frame->count) particles visited at i * step mod count, for
 * a step coprime with count near count / phi: distinct particles spread over
 * the whole array, so files stored layer by layer or block by block are
 * sampled everywhere, not just their first part. xyz gets 3 m floats. */
void fc_spread_sample(const fc_frame *frame, float *xyz, uint64_t m);

/* The typical distance between neighbouring particles of the sample: the
 * median nearest-neighbour distance (to a particle at a different position)
 * of up to 128 of them, which ignores spray and isolated droplets; 0 when
 * they all coincide. A sample of m of n particles has a spacing about
 * (n / m)^(1/3) times the frame's. */
double fc_sample_spacing(const fc_frame *sample);

#endif
