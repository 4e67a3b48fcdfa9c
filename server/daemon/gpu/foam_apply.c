/* foam_apply.c — see foam_apply.h. */
#include "gpu/foam_apply.h"

#include <string.h>

#include "fc_error.h"
#include "uploads/foam_track.h"
#include "uploads/frame_pool.h"

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

fc_code fc_foam_apply(fc_shared_frame *frame, fc_pipeline *p, const fc_settings *settings, fc_error *err)
{
    if (!frame->foam_amplitude)
        return advance(frame, p, settings, err);
    return fc_pipeline_set_amplitudes(p, frame->foam_amplitude, frame->frame.count, err);
}
