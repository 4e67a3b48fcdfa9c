/* view_spacemouse.h — the viewer's SpaceMouse: client/input's service, its
 * filter and motion mapping, applied to the camera once per UI frame with
 * that frame's dt. Without a device (or without USB access) the viewer runs
 * as before; the service says why in one notice line. */
#ifndef FC_VIEW_SPACEMOUSE_H
#define FC_VIEW_SPACEMOUSE_H

#include <stdbool.h>
#include <stdint.h>

#include "spacemouse.h"
#include "spacemouse_filter.h"
#include "spacemouse_motion.h"

typedef struct fc_view_spacemouse {
    fc_spacemouse *service;       /* NULL: not running */
    fc_sm_filter filter;
    fc_sm_motion_config motion;
    uint64_t last_ns;             /* the previous frame's time, for dt */
    bool device;                  /* a device is claimed */
} fc_view_spacemouse;

/* Starts the service; prints a notice and carries on without it on failure. */
void fc_view_spacemouse_start(fc_view_spacemouse *vs, void (*wake)(void *ctx), void *ctx);
void fc_view_spacemouse_stop(fc_view_spacemouse *vs);

/* True while the puck is deflected: the UI then runs at a steady frame rate. */
bool fc_view_spacemouse_moving(const fc_view_spacemouse *vs);

/* What one UI frame got from the SpaceMouse. */
typedef struct fc_view_sm_result {
    bool moved;                   /* the camera changed */
    bool reset;                   /* button 1: reset the camera */
    bool toggle_mode;             /* button 2: orbit <-> fly */
} fc_view_sm_result;

/* Drains the service's events and moves *camera by this frame's motion. */
fc_view_sm_result fc_view_spacemouse_frame(fc_view_spacemouse *vs, fc_sm_mode mode, fc_camera *camera);

#endif
