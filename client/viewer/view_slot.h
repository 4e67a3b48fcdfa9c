/* view_slot.h — the two hand-over points between the UI thread and the
 * network worker, each one mutex-protected value where the newest replaces
 * the older (latest wins: a fast drag never queues a backlog):
 *   request slot  UI -> worker: what to render next (camera, settings, frame)
 *   image slot    worker -> UI: the newest decoded image */
#ifndef FC_VIEW_SLOT_H
#define FC_VIEW_SLOT_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_view_request {
    uint64_t generation;          /* increases with every change the UI makes */
    fc_camera camera;             /* at the window's full size */
    bool has_camera;              /* false: the server frames a session itself */
    fc_settings settings;
    uint32_t frame_index;         /* which file of a sequence */
    bool preview;                 /* the camera is moving: render at half size */
    uint32_t screenshot;          /* > 0: also write a PNG numbered so (p key) */
    uint32_t pick;                /* > 0: find the fluid under (pick_x, pick_y), numbered so (double-click) */
    float pick_x, pick_y;         /* in [0, 1] across the window, y down */
} fc_view_request;

typedef struct fc_view_image {
    uint8_t *rgba;                /* width * height * 4 bytes, rows top to bottom; owned */
    uint32_t width, height;
    uint64_t generation;          /* of the request it answers (0: a session's new frame) */
    uint32_t frame_index;
    uint64_t frame_number;        /* session frames */
    bool preview;
    float stage_ms[FC_STAGE_COUNT];
    double round_trip_ms;         /* request sent -> image decoded */
    uint32_t pick;                /* the pick this answers (0: none) */
    bool picked;                  /* fluid was under it, at pivot */
    float pivot[3];
} fc_view_image;

void fc_view_image_free(fc_view_image *image);

/* Where a followed session stands, as the worker last learnt it (the UI's
 * title and HUD say it). A sequence of files stays FC_VIEW_SESSION_NONE. */
typedef enum fc_view_session_state {
    FC_VIEW_SESSION_NONE = 0,     /* playing files, or not subscribed yet */
    FC_VIEW_SESSION_WAITING,      /* subscribed; the session has no frame yet (no producer, or none published) */
    FC_VIEW_SESSION_LIVE,         /* its frames are coming */
    FC_VIEW_SESSION_ENDED         /* its producers left: the last frame stays, the camera still works */
} fc_view_session_state;

typedef struct fc_view_slots {
    pthread_mutex_t lock;
    pthread_cond_t changed;       /* signalled when the request changes or stop is set */
    fc_view_request request;
    bool stop;
    fc_view_image image;          /* rgba NULL: nothing new */
    char failure[FC_ERROR_MESSAGE_MAX]; /* set once by the worker when it gave up */
    int failure_exit;
    fc_view_session_state session_state;
} fc_view_slots;

fc_code fc_view_slots_init(fc_view_slots *s, fc_error *err);
void fc_view_slots_destroy(fc_view_slots *s);

/* UI side. */
void fc_view_slots_put_request(fc_view_slots *s, const fc_view_request *r);
void fc_view_slots_stop(fc_view_slots *s);
/* Moves the newest image (if any) to *out, which the caller then owns. */
bool fc_view_slots_take_image(fc_view_slots *s, fc_view_image *out);
/* The worker's failure, if it gave up: copies the message, returns its exit status (0: none). */
int fc_view_slots_failure(fc_view_slots *s, char *message, size_t size);
fc_view_session_state fc_view_slots_session_state(fc_view_slots *s);

/* Worker side. Waits up to timeout_ms (< 0: forever) for a request newer than
 * `after`; false when none came or stop was set (*stop says which). */
bool fc_view_slots_wait_request(fc_view_slots *s, uint64_t after, int timeout_ms, fc_view_request *out,
                                bool *stop);
/* Replaces the image slot's contents (freeing an image the UI never took). */
void fc_view_slots_put_image(fc_view_slots *s, fc_view_image *image);
void fc_view_slots_fail(fc_view_slots *s, int exit_status, const char *message);
void fc_view_slots_set_session_state(fc_view_slots *s, fc_view_session_state state);

#endif
