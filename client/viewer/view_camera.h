/* view_camera.h — the viewer's camera: mouse drags and the wheel turned into
 * the same view-frame deltas a SpaceMouse produces (fc_sm_camera_delta), so
 * both inputs move the camera through one function, fc_sm_camera_apply. The
 * pivot of orbit is the camera's target. */
#ifndef FC_VIEW_CAMERA_H
#define FC_VIEW_CAMERA_H

#include <stdbool.h>

#include "fluidcast_types.h"
#include "spacemouse_camera.h"
#include "spacemouse_motion.h"

typedef enum fc_view_drag { FC_VIEW_DRAG_ORBIT, FC_VIEW_DRAG_PAN } fc_view_drag;

/* Radians of orbit per pixel of drag: a drag across the window's height turns
 * the scene by half a turn, whatever the window's size. */
double fc_view_orbit_rad_per_pixel(int window_height);

/* The delta of a drag by (dx, dy) window pixels (y down, as SDL reports). */
fc_sm_camera_delta fc_view_drag_delta(fc_view_drag kind, fc_sm_mode mode, const fc_camera *cam, int dx, int dy,
                                      int window_height);

/* Orbit as a turntable: a horizontal drag turns the scene about the camera's
 * up vector through the pivot, a vertical one tilts it about the view's
 * right axis, and the up vector stays as it was, so the horizon stays level
 * (a free trackball rolls the view after a few circles). A tilt that would
 * look straight along up is refused (FC_ERR_USAGE, camera unchanged). */
fc_code fc_view_turntable(fc_camera *cam, int dx, int dy, int window_height, fc_error *err);

/* The world point at linear view depth `depth` (along the view axis) under
 * the window position (u, v) in [0, 1], v down. False for a degenerate camera. */
bool fc_view_unproject(const fc_camera *cam, float u, float v, float depth, float out[3]);

/* Moves eye and target together so that the target (the pivot) is `pivot`:
 * the view recentres on it, at the same distance and direction. */
void fc_view_set_pivot(fc_camera *cam, const float pivot[3]);

/* The delta of `clicks` wheel clicks (positive: away from the user, closer). */
fc_sm_camera_delta fc_view_wheel_delta(fc_sm_mode mode, float clicks);

#endif
