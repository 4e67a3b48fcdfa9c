/* shared_frame.h — a particle frame shared by reference between the event loop
 * (sessions, viewers) and the GL thread, so publishing one frame to many
 * viewers never copies the particles. Immutable once created, except
 * estimated_radius and foam_amplitude, which only the GL thread touches. */
#ifndef FC_DAEMON_SHARED_FRAME_H
#define FC_DAEMON_SHARED_FRAME_H

#include <stdatomic.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "wire.h"

struct fc_foam_track;
struct fc_frame_pool;

typedef struct fc_shared_frame {
    atomic_uint refs;
    fc_frame frame;           /* its arrays lie in block */
    uint8_t *block;
    size_t block_size;
    struct fc_frame_pool *pool;   /* where block goes back */
    uint64_t id;              /* process-unique: tells the GL thread whether it holds this frame already */
    uint64_t number;          /* the producer's frame number (sessions); 0 for a connection's own FRAME */
    double ready_ms;          /* fc_monotonic_ms() when it was complete: stream images count TOTAL from here */
    float receive_ms;         /* FC_STAGE_RECEIVE: first byte -> last byte of its message(s) */
    float decode_ms;          /* FC_STAGE_DECODE */
    float estimated_radius;   /* GL thread only: 0 until a render with radius "auto" estimated it */
    struct fc_foam_track *foam;   /* the foam history of the stream it belongs to (a reference) */
    float *foam_amplitude;    /* GL thread only: what that history gave each particle (frame order),
                                 in a block of fc_shared_frame_amplitude_bytes from the pool;
                                 NULL until first uploaded */
} fc_shared_frame;

/* Takes over the view's block (the view is emptied; on failure its block goes
 * back to the pool) with one reference, and a reference to `foam`, the history
 * of the stream the frame continues. */
fc_code fc_shared_frame_create(fc_frame_view *view, struct fc_frame_pool *pool, uint64_t id,
                               struct fc_foam_track *foam, fc_shared_frame **out, fc_error *err);
/* Size of the foam_amplitude block: at least one entry, as a non-NULL block
 * is what marks the frame as advanced. */
size_t fc_shared_frame_amplitude_bytes(const fc_shared_frame *f);

fc_shared_frame *fc_shared_frame_ref(fc_shared_frame *f);
/* Drops a reference; the last one frees the frame and gives its block back to the pool. NULL is ignored. Any thread. */
void fc_shared_frame_unref(fc_shared_frame *f);

#endif
