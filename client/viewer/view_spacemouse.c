/* view_spacemouse.c — SpaceMouse events into camera motion. */
#include "view_spacemouse.h"

#include <stdio.h>

#include "spacemouse_camera.h"

#define FRAME_NS 15000000ull

void fc_view_spacemouse_start(fc_view_spacemouse *vs, void (*wake)(void *ctx), void *ctx)
{
    *vs = (fc_view_spacemouse){0};
    fc_sm_filter_config filter;
    fc_sm_filter_config_default(&filter);
    fc_sm_filter_init(&vs->filter, &filter);
    fc_sm_motion_config_default(&vs->motion);
    fc_spacemouse_options options;
    fc_spacemouse_options_default(&options);
    options.wake = wake;
    options.wake_ctx = ctx;
    fc_error err;
    if (fc_spacemouse_start(&options, &vs->service, &err) != FC_OK) {
        fprintf(stderr, "fluidcast: no SpaceMouse (%s); the mouse still works\n", err.message);
        vs->service = NULL;
    }
}

void fc_view_spacemouse_stop(fc_view_spacemouse *vs)
{
    fc_spacemouse_stop(vs->service);
    vs->service = NULL;
}

bool fc_view_spacemouse_moving(const fc_view_spacemouse *vs) { return vs->service && vs->filter.has_motion; }

static void take_event(fc_view_spacemouse *vs, const fc_sm_event *ev, fc_view_sm_result *r)
{
    switch (ev->type) {
    case FC_SM_EVENT_ARRIVED:
        vs->device = true;
        fprintf(stderr, "fluidcast: SpaceMouse: %s\n", ev->name);
        break;
    case FC_SM_EVENT_LEFT:
        vs->device = false;
        fc_sm_filter_init(&vs->filter, &vs->filter.config);
        fprintf(stderr, "fluidcast: SpaceMouse %s unplugged\n", ev->name);
        break;
    case FC_SM_EVENT_NOTICE:
        fprintf(stderr, "fluidcast: SpaceMouse: %s\n", ev->message);
        break;
    case FC_SM_EVENT_REPORT: {
        fc_sm_filter_motion(&vs->filter, &ev->state, ev->time_ns);
        fc_sm_actions a = fc_sm_button_actions(&ev->state);
        r->reset |= a.reset != 0;
        r->toggle_mode |= a.toggle_mode != 0;
        break;
    }
    }
}

static bool any_nonzero(const float v[3]) { return v[0] != 0.0f || v[1] != 0.0f || v[2] != 0.0f; }

fc_view_sm_result fc_view_spacemouse_frame(fc_view_spacemouse *vs, fc_sm_mode mode, fc_camera *camera)
{
    fc_view_sm_result r = {0};
    if (!vs->service)
        return r;
    fc_sm_event ev;
    while (fc_spacemouse_next(vs->service, &ev, 0))
        take_event(vs, &ev, &r);
    uint64_t now = fc_sm_monotonic_ns(NULL);
    /* Reports come every 8-16 ms and each wakes the loop: motion is applied
     * once per frame, with the frame's whole dt, not once per report. */
    if (vs->last_ns && now - vs->last_ns < FRAME_NS)
        return r;
    double dt = vs->last_ns ? (double)(now - vs->last_ns) * 1e-9 : 0.0;
    vs->last_ns = now;
    float axes[FC_SM_AXES];
    fc_sm_filter_output(&vs->filter, now, axes);
    fc_sm_camera_delta d = fc_sm_motion_delta(&vs->motion, axes, mode, dt);
    if (any_nonzero(d.translate) || any_nonzero(d.rotate))
        r.moved = fc_sm_camera_apply(&d, camera, NULL) == FC_OK;
    return r;
}
