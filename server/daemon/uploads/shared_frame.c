/* shared_frame.c — see shared_frame.h. */
#include "uploads/shared_frame.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "uploads/foam_track.h"
#include "uploads/frame_pool.h"

fc_code fc_shared_frame_create(fc_frame_view *view, fc_frame_pool *pool, uint64_t id, fc_foam_track *foam,
                               fc_shared_frame **out, fc_error *err)
{
    fc_shared_frame *f = calloc(1, sizeof *f);
    if (!f) {
        fc_frame_pool_give_view(pool, view);
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a shared frame");
    }
    atomic_init(&f->refs, 1);
    f->frame = view->frame;
    f->block = view->block;
    f->block_size = view->block_size;
    f->pool = pool;
    memset(view, 0, sizeof *view);
    f->id = id;
    f->foam = fc_foam_track_ref(foam);
    f->receive_ms = -1.0f;
    f->decode_ms = -1.0f;
    *out = f;
    return FC_OK;
}

size_t fc_shared_frame_amplitude_bytes(const fc_shared_frame *f)
{
    return (size_t)(f->frame.count > 0 ? f->frame.count : 1) * sizeof *f->foam_amplitude;
}

fc_shared_frame *fc_shared_frame_ref(fc_shared_frame *f)
{
    atomic_fetch_add_explicit(&f->refs, 1, memory_order_relaxed);
    return f;
}

void fc_shared_frame_unref(fc_shared_frame *f)
{
    /* acq_rel: the thread that frees must see every other thread's last use. */
    if (f && atomic_fetch_sub_explicit(&f->refs, 1, memory_order_acq_rel) == 1) {
        fc_frame_pool_give(f->pool, f->block, f->block_size);
        fc_foam_track_unref(f->foam);
        fc_frame_pool_give(f->pool, (uint8_t *)f->foam_amplitude, fc_shared_frame_amplitude_bytes(f));
        free(f);
    }
}
