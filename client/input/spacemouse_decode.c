/* spacemouse_decode.c — report bytes into fc_sm_state. */
#include "spacemouse_decode.h"

#include <string.h>

#define REPORT_MOTION_1 0x01
#define REPORT_MOTION_2 0x02
#define REPORT_BUTTONS 0x03
#define REPORT_BATTERY 0x17
#define REPORT_BUTTON_ARRAY 0x1C
#define REPORT_LONG_PRESS 0x1D
#define SPLIT_LENGTH 7       /* id + three int16 */
#define SIX_AXIS_LENGTH 13   /* id + six int16 */

void fc_sm_state_init(fc_sm_state *state)
{
    memset(state, 0, sizeof *state);
    state->battery_percent = -1;
}

static int16_t read_i16(const uint8_t *p)
{
    return (int16_t)(uint16_t)(p[0] | (p[1] << 8));
}

static float normalise(int16_t raw)
{
    float v = (float)raw / (float)FC_SM_RAW_RANGE;
    return v > 1.0f ? 1.0f : v < -1.0f ? -1.0f : v;
}

/* Three axes starting at `first` from the int16 values at p. */
static void set_axes(fc_sm_state *s, int first, const uint8_t *p)
{
    for (int k = 0; k < 3; k++) {
        s->raw[first + k] = read_i16(p + 2 * k);
        s->axes[first + k] = normalise(s->raw[first + k]);
    }
}

static void set_buttons(fc_sm_state *s, uint32_t buttons)
{
    s->pressed = buttons & ~s->buttons;
    s->released = s->buttons & ~buttons;
    s->buttons = buttons;
}

/* Report 3: bytes after the id are a bitmask, least significant byte first. */
static uint32_t bitmask_buttons(const uint8_t *report, size_t length)
{
    uint32_t buttons = 0;
    for (size_t i = 1; i < length && i <= 4; i++)
        buttons |= (uint32_t)report[i] << (8 * (i - 1));
    return buttons;
}

/* Reports 0x1C/0x1D: uint16 HID button usages, 1 = button 0, 0 = empty slot. */
static uint32_t array_buttons(const uint8_t *report, size_t length)
{
    uint32_t buttons = 0;
    for (size_t i = 1; i + 1 < length; i += 2) {
        uint16_t code = (uint16_t)(report[i] | (report[i + 1] << 8));
        if (code >= 1 && code <= FC_SM_MAX_BUTTONS)
            buttons |= 1u << (code - 1);
    }
    return buttons;
}

static fc_sm_report_kind decode_motion(fc_sm_state *s, const uint8_t *r, size_t length)
{
    if (r[0] == REPORT_MOTION_1 && length >= SIX_AXIS_LENGTH) {
        set_axes(s, FC_SM_X, r + 1);
        set_axes(s, FC_SM_RX, r + 7);
        return FC_SM_REPORT_SIX_AXIS;
    }
    if (length < SPLIT_LENGTH)
        return FC_SM_REPORT_IGNORED;
    set_axes(s, r[0] == REPORT_MOTION_1 ? FC_SM_X : FC_SM_RX, r + 1);
    return r[0] == REPORT_MOTION_1 ? FC_SM_REPORT_TRANSLATION : FC_SM_REPORT_ROTATION;
}

fc_sm_report_kind fc_sm_decode(fc_sm_state *s, const uint8_t *r, size_t length)
{
    s->pressed = s->released = 0;
    if (length < 2)
        return FC_SM_REPORT_IGNORED;
    switch (r[0]) {
    case REPORT_MOTION_1:
    case REPORT_MOTION_2:
        return decode_motion(s, r, length);
    case REPORT_BUTTONS:
        if (s->button_array)
            return FC_SM_REPORT_IGNORED;
        set_buttons(s, bitmask_buttons(r, length));
        return FC_SM_REPORT_BUTTONS;
    case REPORT_BUTTON_ARRAY:
        s->button_array = true;
        set_buttons(s, array_buttons(r, length));
        return FC_SM_REPORT_BUTTON_ARRAY;
    case REPORT_LONG_PRESS:
        s->long_presses = array_buttons(r, length);
        return FC_SM_REPORT_LONG_PRESS;
    case REPORT_BATTERY:
        s->battery_percent = r[1] > 100 ? 100 : r[1];
        return FC_SM_REPORT_BATTERY;
    default:
        return FC_SM_REPORT_IGNORED;
    }
}

bool fc_sm_report_is_motion(fc_sm_report_kind kind)
{
    return kind == FC_SM_REPORT_TRANSLATION || kind == FC_SM_REPORT_ROTATION ||
           kind == FC_SM_REPORT_SIX_AXIS;
}

const char *fc_sm_report_kind_name(fc_sm_report_kind kind)
{
    switch (kind) {
    case FC_SM_REPORT_TRANSLATION: return "translation";
    case FC_SM_REPORT_ROTATION: return "rotation";
    case FC_SM_REPORT_SIX_AXIS: return "six-axis";
    case FC_SM_REPORT_BUTTONS: return "buttons";
    case FC_SM_REPORT_BUTTON_ARRAY: return "button-array";
    case FC_SM_REPORT_LONG_PRESS: return "long-press";
    case FC_SM_REPORT_BATTERY: return "battery";
    case FC_SM_REPORT_IGNORED: break;
    }
    return "ignored";
}
