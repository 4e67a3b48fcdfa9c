/* foam_track.c — see foam_track.h. */
#include "uploads/foam_track.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "uploads/frame_pool.h"

fc_code fc_foam_track_create(fc_foam_track **out, fc_error *err)
{
    fc_foam_track *t = calloc(1, sizeof *t);
    if (!t)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a foam history");
    fc_code code = fc_foam_state_create(&t->state, err);
    if (code != FC_OK) {
        free(t);
        return code;
    }
    atomic_init(&t->refs, 1);
    *out = t;
    return FC_OK;
}

fc_foam_track *fc_foam_track_ref(fc_foam_track *t)
{
    atomic_fetch_add_explicit(&t->refs, 1, memory_order_relaxed);
    return t;
}

void fc_foam_track_unref(fc_foam_track *t)
{
    /* acq_rel: the thread that frees must see the GL thread's last advance. */
    if (t && atomic_fetch_sub_explicit(&t->refs, 1, memory_order_acq_rel) == 1) {
        fc_foam_state_destroy(t->state);
        free(t);
    }
}

/* Advances the track by a frame it has not seen. The copy is allocated
 * first: once advanced, the frame must keep its amplitudes, or a later upload
 * would advance the track by the same frame again. */
static fc_code advance(fc_shared_frame *frame, fc_pipeline *p, const fc_settings *settings, fc_error *err)
{
    uint64_t count = frame->frame.count;
    float *kept = (float *)fc_frame_pool_take(frame->pool, fc_shared_frame_amplitude_bytes(frame));
    if (!kept)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the foam amplitudes of %llu particles",
                            (unsigned long long)count);
    fc_code code = fc_foam_state_advance(frame->foam->state, p, &frame->frame, settings, err);
    if (code != FC_OK) {
        fc_frame_pool_give(frame->pool, (uint8_t *)kept, fc_shared_frame_amplitude_bytes(frame));
        return code;
    }
    if (count > 0)
        memcpy(kept, fc_foam_state_amplitudes(frame->foam->state), count * sizeof *kept);
    frame->foam_amplitude = kept;
    return FC_OK;
}

fc_code fc_foam_track_apply(fc_shared_frame *frame, fc_pipeline *p, const fc_settings *settings, fc_error *err)
{
    if (!frame->foam_amplitude)
        return advance(frame, p, settings, err);
    return fc_pipeline_set_amplitudes(p, frame->foam_amplitude, frame->frame.count, err);
}
