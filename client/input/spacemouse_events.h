/* spacemouse_events.h — what the SpaceMouse service tells its user, and the
 * thread-safe queue that carries it from the libusb event thread.
 *
 * The queue is the library's whole interface towards a viewer: the event
 * thread never calls into viewer code except the optional wake-up callback
 * (e.g. one SDL_PushEvent) after queueing. */
#ifndef FC_SPACEMOUSE_EVENTS_H
#define FC_SPACEMOUSE_EVENTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "spacemouse_decode.h"

#define FC_SM_REPORT_MAX 64       /* bytes requested per interrupt transfer */
#define FC_SM_NAME_MAX 48

typedef enum fc_sm_event_type {
    FC_SM_EVENT_ARRIVED = 1,      /* a SpaceMouse was opened and claimed */
    FC_SM_EVENT_REPORT,           /* a report arrived: raw bytes and the state after it */
    FC_SM_EVENT_LEFT,             /* the device went away (unplugged): not an error */
    FC_SM_EVENT_NOTICE            /* a device could not be used (e.g. permissions): message says why */
} fc_sm_event_type;

typedef struct fc_sm_event {
    fc_sm_event_type type;
    uint64_t time_ns;             /* the service's clock when it was queued */
    uint16_t vendor, product;
    uint8_t bus, address;
    char name[FC_SM_NAME_MAX];    /* the model's name */
    /* FC_SM_EVENT_REPORT */
    uint8_t report[FC_SM_REPORT_MAX];
    size_t length;                /* actual_length of the transfer */
    fc_sm_report_kind kind;
    fc_sm_state state;            /* the device's state after this report */
    uint32_t dropped;             /* events lost before this one (queue full) */
    /* FC_SM_EVENT_NOTICE, FC_SM_EVENT_LEFT (how it left) */
    char message[FC_ERROR_MESSAGE_MAX];
} fc_sm_event;

typedef struct fc_sm_queue fc_sm_queue;

/* A queue of `capacity` events (>= 1). */
fc_code fc_sm_queue_create(size_t capacity, fc_sm_queue **out, fc_error *err);
void fc_sm_queue_destroy(fc_sm_queue *queue);

/* Appends a copy of *event. When full, the oldest event is dropped (motion is
 * deflection, so the newest matters most) and the next event popped says how
 * many were lost. */
void fc_sm_queue_push(fc_sm_queue *queue, const fc_sm_event *event);

/* Takes the oldest event; waits up to timeout_ms (0: no wait, < 0: forever).
 * False when none came. */
bool fc_sm_queue_pop(fc_sm_queue *queue, fc_sm_event *event, int timeout_ms);

#endif
