/* snapshot_camera.h — the camera `fluidcast snapshot` renders with: the one the
 * options spell out, or one that frames the particles, upright. */
#ifndef FC_SNAPSHOT_CAMERA_H
#define FC_SNAPSHOT_CAMERA_H

#include <stdbool.h>

#include "fluidcast_types.h"
#include "framing_bounds.h"
#include "snapshot_options.h"
#include "up_choice.h"

/* With --eye/--target: that look-at camera, with up->up (a guessed up the
 * view looks straight along is replaced first: fc_up_choice_fit_view).
 * Without: the box (a frame's or a sequence's framing box, framing_bounds.h)
 * framed from above as seen with up->up (fc_box_upright), moved along the
 * view axis so it still fits a --fov other than the default. FC_ERR_USAGE
 * when the result is not a valid camera (e.g. --up parallel to the view
 * direction). */
fc_code fc_snapshot_camera(const fc_snapshot_options *o, const fc_framing_box *box, fc_up_choice *up,
                           fc_camera *cam, fc_error *err);

/* Without --eye/--target, when the box leaves particles out: "framing: the
 * fluid without N particles far from it (--eye/--target to frame them)" on
 * stdout; "up to N particles a frame" for a sequence's box. */
void fc_snapshot_print_left_out(const fc_framing_box *box, bool sequence);

#endif
