/* sloshing_block.h — the example "simulation": water in a 2 x 1 tank whose
 * free surface tilts back and forth, sampled on a lattice. Analytic, so the
 * examples need no solver; what matters is how the frames are sent. */
#ifndef FC_EXAMPLE_SLOSHING_BLOCK_H
#define FC_EXAMPLE_SLOSHING_BLOCK_H

#include <stdint.h>

#include "fluidcast_types.h"

#define SLOSH_TANK_LENGTH 2.0f     /* x extent */
#define SLOSH_PERIOD_FRAMES 48     /* frames per slosh back and forth */

/* Frame `step` of the slosh: the particles whose x lies in [x_begin, x_end),
 * with velocities and persistent ids. The arrays are allocated (free with
 * fc_frame_free). The whole tank is [0, SLOSH_TANK_LENGTH). */
fc_code slosh_frame(uint32_t step, float x_begin, float x_end, fc_frame *out, fc_error *err);

#endif
