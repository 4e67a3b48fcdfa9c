/* foam_track.c — see foam_track.h. */
#include "uploads/foam_track.h"

#include <stdlib.h>

#include "fc_error.h"

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
