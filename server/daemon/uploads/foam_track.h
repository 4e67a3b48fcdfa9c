/* foam_track.h — the foam history of one particle stream (a connection's own
 * FRAMEs, or a named session's frames, shared by all its viewers): an
 * fc_foam_state that its frames hold by reference, so it outlives the
 * connection or session while any of its frames waits for the GL thread.
 *
 * The state advances once per frame, when the GL thread first uploads that
 * frame, with the settings of that first render (gpu/foam_apply.h). Frames
 * nobody renders (latest wins) never reach the GL thread, so a jump in
 * velocity is measured between the frames of the stream that were shown. */
#ifndef FC_DAEMON_FOAM_TRACK_H
#define FC_DAEMON_FOAM_TRACK_H

#include <stdatomic.h>

#include "fluidcast_types.h"
#include "render/pipeline.h"

typedef struct fc_foam_track {
    atomic_uint refs;
    fc_foam_state *state;   /* CPU only; used by the GL thread alone once frames hold the track */
} fc_foam_track;

/* A fresh history (nothing seen yet) with one reference. */
fc_code fc_foam_track_create(fc_foam_track **out, fc_error *err);
fc_foam_track *fc_foam_track_ref(fc_foam_track *t);
/* Drops a reference; the last one frees the history. NULL is ignored. Any thread. */
void fc_foam_track_unref(fc_foam_track *t);

#endif
