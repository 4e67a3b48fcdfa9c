/* fuzz_packed.h — the checks of a packed body (PROTOCOL.md 10.9) that a
 * decoder accepted: FRAME_PACKED's payload, or CHUNK's after its header. */
#ifndef FC_FUZZ_PACKED_H
#define FC_FUZZ_PACKED_H

#include "fluidcast_types.h"
#include "fuzz_stream.h"

/* `decoded` is what the decoder made of `body` with every encoding allowed and
 * at most FUZZ_MAX_PARTICLES particles. Aborts on any broken invariant. */
void fuzz_check_packed_body(fuzz_payload body, const fc_frame *decoded);

#endif
