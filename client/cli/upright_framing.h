/* upright_framing.h — the auto-framing camera turned so that "up" in the
 * picture is a given world direction, seen from above the fluid as with +z. */
#ifndef FC_UPRIGHT_FRAMING_H
#define FC_UPRIGHT_FRAMING_H

#include <stdint.h>

#include "fluidcast_types.h"

/* fc_camera_frame_bounds (which assumes +z up: it looks down at the box from
 * the +x,-y,+z side) with its eye turned about the box centre by the shortest
 * rotation taking +z to `up`, so the view keeps looking down on the fluid, and
 * cam->up = up. The distance, and so the framing, is unchanged. A zero `up`
 * leaves the eye where +z puts it (fc_camera_validate rejects such a camera). */
void fc_frame_upright(const fc_frame *frame, uint32_t width, uint32_t height, const float up[3], fc_camera *cam);

#endif
