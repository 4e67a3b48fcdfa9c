/* snapshot_camera.h — the camera `fluidcast snapshot` renders with: the one the
 * options spell out, or one that frames the particles, upright. */
#ifndef FC_SNAPSHOT_CAMERA_H
#define FC_SNAPSHOT_CAMERA_H

#include "fluidcast_types.h"
#include "snapshot_options.h"
#include "up_choice.h"

/* With --eye/--target: that look-at camera, with up->up (a guessed up the
 * view looks straight along is replaced first: fc_up_choice_fit_view).
 * Without: the particles framed from above as seen with up->up
 * (fc_frame_upright), moved along the view axis so they still fit a --fov
 * other than the default. FC_ERR_USAGE when the result is not a valid camera
 * (e.g. --up parallel to the view direction). frame->count must be > 0. */
fc_code fc_snapshot_camera(const fc_snapshot_options *o, const fc_frame *frame, fc_up_choice *up, fc_camera *cam,
                           fc_error *err);

#endif
