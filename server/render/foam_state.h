/* foam_state.h — the foam state's inner workings that tests may observe
 * (fc_foam_state itself is declared in pipeline.h). */
#ifndef FC_FOAM_STATE_H
#define FC_FOAM_STATE_H

#include <stdint.h>

#include "pipeline.h"

/* The noise amplitude multiplier the last advance gave the particle `id`:
 * 1 when calm, more after a jump in velocity; 1 for ids it has not seen. */
float fc_foam_state_amplitude(const fc_foam_state *s, uint32_t id);

#endif
