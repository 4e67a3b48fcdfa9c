/* snapshot_camera.h — the camera `fluidcast snapshot` renders with: the one the
 * options spell out, or one that frames the particles. */
#ifndef FC_SNAPSHOT_CAMERA_H
#define FC_SNAPSHOT_CAMERA_H

#include "fluidcast_types.h"
#include "snapshot_options.h"

/* With --eye/--target: that look-at camera. Without: fc_camera_frame_bounds,
 * moved along its view axis so the particles still fit a --fov other than the
 * default, and given --up when set. FC_ERR_USAGE when the result is not a valid
 * camera (e.g. --up parallel to the view direction). frame->count must be > 0. */
fc_code fc_snapshot_camera(const fc_snapshot_options *o, const fc_frame *frame, fc_camera *cam,
                           fc_error *err);

#endif
