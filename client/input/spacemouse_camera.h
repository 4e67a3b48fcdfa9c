/* spacemouse_camera.h — applying a SpaceMouse frame delta to an fc_camera. */
#ifndef FC_SPACEMOUSE_CAMERA_H
#define FC_SPACEMOUSE_CAMERA_H

#include "fluidcast_types.h"
#include "spacemouse_motion.h"

/* Moves *camera by delta (see spacemouse_motion.h for what each mode means).
 * Orbit keeps the eye-target distance except for the z translation (dolly,
 * multiplicative so the eye never crosses the target); fly keeps it exactly.
 * Fails, leaving *camera unchanged, when the camera is degenerate (eye ==
 * target, up parallel to the view). */
fc_code fc_sm_camera_apply(const fc_sm_camera_delta *delta, fc_camera *camera, fc_error *err);

#endif
