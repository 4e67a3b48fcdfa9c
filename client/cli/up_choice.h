/* up_choice.h — the up direction a command renders with: --up when given,
 * otherwise the axis guessed from the particles (up_axis.h), and the note
 * that tells the user which one was used and why. */
#ifndef FC_UP_CHOICE_H
#define FC_UP_CHOICE_H

#include <stdbool.h>

#include "fluidcast_types.h"

typedef struct fc_up_choice {
    float up[3];
    bool given;        /* from --up: nothing to report */
    /* Without --up, e.g. "+y (guessed from the particles; --up to override)"
     * or "+z (default: no floor among the particles; --up to override)". */
    char note[128];
} fc_up_choice;

/* `given` when has_up, else the guess for `frame`. FC_ERR_NOMEM from the guess. */
fc_code fc_up_choose(bool has_up, const float given[3], const fc_frame *frame, fc_up_choice *out, fc_error *err);

/* For an explicit --eye/--target: a guessed up that the view looks straight
 * along cannot orient the picture; then +z (or +y when the view is along z)
 * takes its place and the note says so ("+z (the view looks along +y; ...)"). A given up is left alone (the camera
 * check rejects it with its reason). */
void fc_up_choice_fit_view(fc_up_choice *c, const float eye[3], const float target[3]);

#endif
