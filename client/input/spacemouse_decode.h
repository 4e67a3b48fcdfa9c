/* spacemouse_decode.h — a SpaceMouse HID report (bytes off the interrupt
 * endpoint) into the device's state: six axes and the buttons.
 *
 * Pure: no I/O, no clock. Layouts are told apart by report id and length, not
 * by product id, because sources disagree per model (SPACEMOUSE-NOTES.md):
 *   id 1, 7 bytes      translation X, Y, Z             (split reports)
 *   id 1, 13 bytes     translation and rotation        (newer devices)
 *   id 2, 7 bytes      rotation RX, RY, RZ             (split reports)
 *   id 3, 1 + n bytes  button bitmask, bit 0 = button 0
 *   id 0x1C, 13 bytes  up to six uint16 codes of pressed buttons (1 = button 0);
 *                      once seen, report 3 is ignored for that device, since
 *                      such devices send both and only 0x1C has every button
 *   id 0x1D, 13 bytes  the same for long presses
 *   id 0x17, 3 bytes   battery percentage
 * Values are little-endian int16 in the device's frame: +X right, +Y towards
 * the user, +Z pushing down, rotations right-handed about those axes. */
#ifndef FC_SPACEMOUSE_DECODE_H
#define FC_SPACEMOUSE_DECODE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define FC_SM_AXES 6
/* Logical range of every captured descriptor: values are normalised by 1/350. */
#define FC_SM_RAW_RANGE 350
/* Buttons beyond 32 (the Enterprise has 31) are dropped. */
#define FC_SM_MAX_BUTTONS 32

enum fc_sm_axis { FC_SM_X = 0, FC_SM_Y, FC_SM_Z, FC_SM_RX, FC_SM_RY, FC_SM_RZ };

typedef enum fc_sm_report_kind {
    FC_SM_REPORT_IGNORED = 0,     /* unknown id, too short, or report 3 after 0x1C */
    FC_SM_REPORT_TRANSLATION,     /* id 1, 7 bytes */
    FC_SM_REPORT_ROTATION,        /* id 2, 7 bytes */
    FC_SM_REPORT_SIX_AXIS,        /* id 1, 13 bytes */
    FC_SM_REPORT_BUTTONS,         /* id 3 */
    FC_SM_REPORT_BUTTON_ARRAY,    /* id 0x1C */
    FC_SM_REPORT_LONG_PRESS,      /* id 0x1D */
    FC_SM_REPORT_BATTERY          /* id 0x17 */
} fc_sm_report_kind;

/* The device as last reported. Axes hold until the next report of their kind:
 * the device sends deflection, not deltas. pressed/released are the edges the
 * latest report caused (cleared by every report). */
typedef struct fc_sm_state {
    int16_t raw[FC_SM_AXES];      /* as sent */
    float axes[FC_SM_AXES];       /* raw / 350, clamped to [-1, 1] */
    uint32_t buttons;             /* bit i: button i held */
    uint32_t pressed;             /* bits that went 0 -> 1 with the latest report */
    uint32_t released;            /* bits that went 1 -> 0 with the latest report */
    uint32_t long_presses;        /* bit i: button i long-pressed (report 0x1D) */
    int battery_percent;          /* -1 until a battery report */
    bool button_array;            /* a 0x1C report was seen: report 3 is ignored */
} fc_sm_state;

/* A state with everything at rest. */
void fc_sm_state_init(fc_sm_state *state);

/* Applies one report of `length` bytes (byte 0 = report id) to *state and
 * says what it was. An ignored report changes nothing but the edges. */
fc_sm_report_kind fc_sm_decode(fc_sm_state *state, const uint8_t *report, size_t length);

/* True for the kinds that carry axes. */
bool fc_sm_report_is_motion(fc_sm_report_kind kind);

/* A stable lower-case name: "translation", "six-axis", "buttons", ... */
const char *fc_sm_report_kind_name(fc_sm_report_kind kind);

#endif
