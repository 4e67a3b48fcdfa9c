/* spacemouse_motion.h — filtered SpaceMouse axes into one frame's camera
 * motion (a pure function of axes, mode and dt), and buttons into actions.
 *
 * Device frame to view frame (x right, y up, z towards the viewer):
 *     T = (X, -Z, Y)      R = (RX, -RZ, RY)
 * (device: +X right, +Y towards the user, +Z pushing down). The signs were
 * derived from spacenavd/libspnav, not checked on hardware, and users disagree
 * about conventions, so each view axis has its own configurable sign.
 *
 * Two modes:
 *   orbit  the scene is held in the hand: pushing the puck right moves the
 *          scene right, twisting it turns the scene about the pivot (the
 *          camera's target), pulling it towards the viewer brings the scene
 *          closer (dolly);
 *   fly    the camera is held in the hand: pushing forward flies forward,
 *          twisting turns the camera about its own eye.
 * Translation speed is a fraction of the eye-target distance per second so it
 * feels the same at every zoom; rotation speed is in radians per second. Both
 * are at full deflection and scale with the frame's dt. */
#ifndef FC_SPACEMOUSE_MOTION_H
#define FC_SPACEMOUSE_MOTION_H

#include <stdint.h>

#include "spacemouse_decode.h"

typedef enum fc_sm_mode { FC_SM_MODE_ORBIT = 0, FC_SM_MODE_FLY = 1 } fc_sm_mode;

typedef struct fc_sm_motion_config {
    float translate_sign[3];      /* per view axis x, y, z: +1 or -1 */
    float rotate_sign[3];
    float translate_speed;        /* eye-target distances per second at full deflection */
    float rotate_speed;           /* radians per second at full deflection */
    float max_dt;                 /* longer frames count as this (s): a stall must not jump */
} fc_sm_motion_config;

/* One frame's motion in the view frame. translate is in eye-target distances,
 * rotate an axis-angle vector in radians. */
typedef struct fc_sm_camera_delta {
    fc_sm_mode mode;
    float translate[3];
    float rotate[3];
} fc_sm_camera_delta;

/* Signs +1, 1 distance/s, pi/2 rad/s, max_dt 0.1 s. */
void fc_sm_motion_config_default(fc_sm_motion_config *config);

/* The frame's delta from filtered device-frame axes (fc_sm_filter_output)
 * over dt seconds; dt <= 0 gives no motion. */
fc_sm_camera_delta fc_sm_motion_delta(const fc_sm_motion_config *config,
                                      const float axes[FC_SM_AXES], fc_sm_mode mode, double dt);

/* What the buttons asked for with one report. */
typedef struct fc_sm_actions {
    int reset;                    /* nonzero: reset the camera */
    int toggle_mode;              /* nonzero: switch orbit <-> fly */
} fc_sm_actions;

#define FC_SM_BUTTON_RESET 0
#define FC_SM_BUTTON_MODE 1

/* Actions from a report's press edges (button 0 reset, button 1 mode): edges,
 * not held bits, so a held button fires once. */
fc_sm_actions fc_sm_button_actions(const fc_sm_state *state);

/* The other mode. */
fc_sm_mode fc_sm_mode_toggle(fc_sm_mode mode);

#endif
