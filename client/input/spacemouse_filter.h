/* spacemouse_filter.h — from the device's last reported deflection to the
 * values a frame should use: held with a watchdog, then per-axis remap, sign,
 * dead zone, dominant-axis mode and sensitivity.
 *
 * The device repeats its deflection every 8-16 ms while the puck is held and
 * sends zeros (three times) on release. A lost zero report must not leave the
 * camera spinning, so a value older than the watchdog reads as zero. Time is
 * passed in (nanoseconds from any monotonic clock): the filter never reads a
 * clock itself, which is what lets tests drive it. */
#ifndef FC_SPACEMOUSE_FILTER_H
#define FC_SPACEMOUSE_FILTER_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "spacemouse_decode.h"

#define FC_SM_WATCHDOG_NS_DEFAULT 200000000ull   /* 200 ms */

typedef struct fc_sm_filter_config {
    /* Output axis i takes input axis source[i] (identity by default). */
    uint8_t source[FC_SM_AXES];
    /* +1 or -1 per output axis. */
    int8_t sign[FC_SM_AXES];
    /* Normalised dead zone per output axis, in [0, 1): smaller magnitudes read
     * as zero and the rest is rescaled so the response starts at 0 (no jump).
     * Default 2/350, spacenavd's 2 raw units. */
    float dead_zone[FC_SM_AXES];
    /* Multiplier per output axis, applied last. */
    float sensitivity[FC_SM_AXES];
    /* Keep only the axis of largest magnitude (after the dead zone, before
     * sensitivity), zeroing the others: for users who want pure motions. */
    bool dominant_axis;
    /* A deflection older than this reads as zero; 0 disables the watchdog. */
    uint64_t watchdog_ns;
} fc_sm_filter_config;

typedef struct fc_sm_filter {
    fc_sm_filter_config config;
    float held[FC_SM_AXES];       /* last reported deflection, device axes */
    uint64_t last_motion_ns;
    bool has_motion;
} fc_sm_filter;

/* Identity remap, signs +1, dead zone 2/350, sensitivity 1, no dominant axis,
 * watchdog 200 ms. */
void fc_sm_filter_config_default(fc_sm_filter_config *config);

/* Rejects a source index out of range, a sign other than +-1, a dead zone
 * outside [0, 1) or a non-finite sensitivity, with the axis named. */
fc_code fc_sm_filter_config_validate(const fc_sm_filter_config *config, fc_error *err);

/* A filter at rest. The config is copied. */
void fc_sm_filter_init(fc_sm_filter *filter, const fc_sm_filter_config *config);

/* A motion report arrived at now_ns: the decoded state's axes become the held
 * deflection. Only motion reports refresh the watchdog. */
void fc_sm_filter_motion(fc_sm_filter *filter, const fc_sm_state *state, uint64_t now_ns);

/* The axes a frame at now_ns should use (output order, after remap). */
void fc_sm_filter_output(const fc_sm_filter *filter, uint64_t now_ns, float out[FC_SM_AXES]);

#endif
