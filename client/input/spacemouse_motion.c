/* spacemouse_motion.c — axes to a camera delta; buttons to actions. */
#include "spacemouse_motion.h"

#include <string.h>

void fc_sm_motion_config_default(fc_sm_motion_config *c)
{
    memset(c, 0, sizeof *c);
    for (int k = 0; k < 3; k++)
        c->translate_sign[k] = c->rotate_sign[k] = 1.0f;
    c->translate_speed = 1.0f;
    c->rotate_speed = 1.5707963f;
    c->max_dt = 0.1f;
}

fc_sm_camera_delta fc_sm_motion_delta(const fc_sm_motion_config *c, const float a[FC_SM_AXES],
                                      fc_sm_mode mode, double dt)
{
    fc_sm_camera_delta d;
    memset(&d, 0, sizeof d);
    d.mode = mode;
    if (!(dt > 0.0))
        return d;
    float t = (float)(dt > c->max_dt ? c->max_dt : dt);
    /* T = (X, -Z, Y), R = (RX, -RZ, RY): see the header. */
    const float view_t[3] = {a[FC_SM_X], -a[FC_SM_Z], a[FC_SM_Y]};
    const float view_r[3] = {a[FC_SM_RX], -a[FC_SM_RZ], a[FC_SM_RY]};
    for (int k = 0; k < 3; k++) {
        d.translate[k] = c->translate_sign[k] * view_t[k] * c->translate_speed * t;
        d.rotate[k] = c->rotate_sign[k] * view_r[k] * c->rotate_speed * t;
    }
    return d;
}

fc_sm_actions fc_sm_button_actions(const fc_sm_state *s)
{
    fc_sm_actions a;
    a.reset = (s->pressed >> FC_SM_BUTTON_RESET) & 1u;
    a.toggle_mode = (s->pressed >> FC_SM_BUTTON_MODE) & 1u;
    return a;
}

fc_sm_mode fc_sm_mode_toggle(fc_sm_mode mode)
{
    return mode == FC_SM_MODE_ORBIT ? FC_SM_MODE_FLY : FC_SM_MODE_ORBIT;
}
