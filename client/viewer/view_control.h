/* view_control.h — the viewer's interactive state on the UI thread: the
 * camera and how input moves it, playback, and when to ask the worker for
 * what (the preview while moving, the full-size image once still, the render
 * size once a resize settles). Requests go out through the request slot, so
 * only the newest matters. */
#ifndef FC_VIEW_CONTROL_H
#define FC_VIEW_CONTROL_H

#include <SDL.h>
#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "spacemouse_motion.h"
#include "view_slot.h"

/* The camera counts as still this long after its last change. */
#define FC_VIEW_STILL_MS 300.0
/* A window resize is applied this long after its last step. */
#define FC_VIEW_RESIZE_MS 150.0

typedef struct fc_view_control {
    fc_view_slots *slots;
    fc_view_request sent;         /* the last request put in the slot */
    fc_camera home;               /* r resets to it */
    fc_sm_mode mode;
    uint32_t file_count;
    double fps;
    bool playing;
    bool frame_seen;              /* the current frame has shown */
    double frame_started_ms;      /* when it first showed */
    bool moving;                  /* a preview went out and the full image has not */
    double moved_ms;
    bool resize_pending;
    double resized_ms;
    int window_width, window_height; /* for the drag's scale and picking */
    bool session;                 /* following a session: no particles here, no picking */
    int drag_button;              /* 0: no drag */
    bool quit;
} fc_view_control;

void fc_view_control_init(fc_view_control *c, fc_view_slots *slots, const fc_camera *home, bool has_camera,
                          const fc_settings *settings, uint32_t file_count, double fps);

/* Handles one SDL event (mouse, keys, window). */
void fc_view_control_event(fc_view_control *c, const SDL_Event *e, double now_ms);

/* An image of sequence frame `frame_index` went on screen. */
void fc_view_control_image_shown(fc_view_control *c, uint32_t frame_index, double now_ms);

/* Time-driven work: the full image once still, a settled resize, playback. */
void fc_view_control_tick(fc_view_control *c, double now_ms);

/* An image answered a double-click: recentre on the picked point, if any. */
void fc_view_control_picked(fc_view_control *c, const fc_view_image *img, double now_ms);

/* The camera was moved by another input (the SpaceMouse). */
void fc_view_control_camera_moved(fc_view_control *c, const fc_camera *cam, double now_ms);
void fc_view_control_reset(fc_view_control *c, double now_ms);
void fc_view_control_toggle_mode(fc_view_control *c);

/* The window's drawable size changed (or is first known). */
void fc_view_control_resized(fc_view_control *c, int width, int height, double now_ms);

/* Milliseconds until the next timed step is due (for the event wait). */
int fc_view_control_wait_ms(const fc_view_control *c, double now_ms);

/* Settled: the last request was full size and the camera is not moving. */
bool fc_view_control_settled(const fc_view_control *c);

const char *fc_view_smoothing_name(fc_smoothing s);

#endif
