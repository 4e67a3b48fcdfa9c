/* upright_framing.h — the auto-framing camera turned so that "up" in the
 * picture is a given world direction, seen from above the fluid as with +z. */
#ifndef FC_UPRIGHT_FRAMING_H
#define FC_UPRIGHT_FRAMING_H

#include <stdint.h>

#include "fluidcast_types.h"
#include "framing_bounds.h"

/* fc_camera_frame_bounds of the box (which assumes +z up: it looks down at
 * the box from the +x,-y,+z side) with its eye turned about the box centre by
 * the shortest rotation taking +z to `up`, so the view keeps looking down on
 * the fluid, and cam->up = up. The distance, and so the framing, is
 * unchanged. A zero `up` leaves the eye where +z puts it (fc_camera_validate
 * rejects such a camera). */
void fc_box_upright(const fc_framing_box *box, uint32_t width, uint32_t height, const float up[3], fc_camera *cam);

/* fc_box_upright of the frame's framing box (framing_bounds.h: the fluid, not
 * the droplets flung far from it). FC_ERR_NOMEM from fc_framing_box_of. */
fc_code fc_frame_upright(const fc_frame *frame, uint32_t width, uint32_t height, const float up[3], fc_camera *cam,
                         fc_error *err);

#endif
