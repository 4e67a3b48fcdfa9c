/* spacemouse.h — the SpaceMouse service: reads a 3Dconnexion SpaceMouse
 * directly through libusb-1.0 (no spacenavd) on its own event thread and hands
 * events to its user through a queue.
 *
 *     fc_spacemouse_options opt;
 *     fc_spacemouse_options_default(&opt);
 *     opt.wake = push_sdl_event;           // optional: called after each event
 *     fc_spacemouse *sm;
 *     if (fc_spacemouse_start(&opt, &sm, &err) == FC_OK) {
 *         fc_sm_event ev;
 *         while (fc_spacemouse_next(sm, &ev, 0)) ...   // e.g. once per frame
 *         fc_spacemouse_stop(sm);
 *     }
 *
 * Devices come and go at any time (hotplug, including those present at
 * start): ARRIVED when one is opened and claimed, LEFT when it is unplugged
 * (not an error), NOTICE when one cannot be used, with the reason (permission
 * denied names the udev rule) — the service carries on without it. One device
 * is used at a time; others that arrive meanwhile wait their turn (up to 8).
 * Start fails only when libusb itself cannot start. */
#ifndef FC_SPACEMOUSE_H
#define FC_SPACEMOUSE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "spacemouse_events.h"

typedef struct fc_spacemouse fc_spacemouse;

/* Where event times come from: injected so a viewer and its filter share one
 * clock (and tests can choose it). */
typedef struct fc_sm_clock {
    uint64_t (*now_ns)(void *ctx);
    void *ctx;
} fc_sm_clock;

typedef struct fc_spacemouse_options {
    fc_sm_clock clock;            /* now_ns NULL: CLOCK_MONOTONIC */
    /* Called on the event thread after each queued event; must be thread-safe
     * and quick (SDL_PushEvent is). NULL: poll only. */
    void (*wake)(void *ctx);
    void *wake_ctx;
    size_t queue_capacity;        /* 0: 1024 */
} fc_spacemouse_options;

void fc_spacemouse_options_default(fc_spacemouse_options *options);

/* CLOCK_MONOTONIC in nanoseconds (the default clock). */
uint64_t fc_sm_monotonic_ns(void *unused);

/* Starts libusb, watches for SpaceMice (hotplug, enumerating those present)
 * and starts the event thread. */
fc_code fc_spacemouse_start(const fc_spacemouse_options *options, fc_spacemouse **out,
                            fc_error *err);

/* The next event, waiting up to timeout_ms (0: do not wait, < 0: forever). */
bool fc_spacemouse_next(fc_spacemouse *sm, fc_sm_event *event, int timeout_ms);

/* Stops the thread, cancels the transfer, releases the interface and gives
 * it back to the kernel driver, closes libusb. NULL is ignored. */
void fc_spacemouse_stop(fc_spacemouse *sm);

#endif
