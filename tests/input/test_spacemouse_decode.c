/* test_spacemouse_decode.c — the report decoder on byte arrays: every layout
 * by id and length, normalisation and clamping, button edges, the button-array
 * reports and the device table. */
#include <string.h>

#include "spacemouse_decode.h"
#include "spacemouse_devices.h"
#include "test_util.h"

#define DECODE(s, ...)                                                  \
    fc_sm_decode((s), (const uint8_t[]){__VA_ARGS__}, sizeof((const uint8_t[]){__VA_ARGS__}))

static void test_split_reports(void)
{
    fc_sm_state s;
    fc_sm_state_init(&s);
    CHECK_CODE(DECODE(&s, 0x01, 10, 0, 20, 0, 30, 0), FC_SM_REPORT_TRANSLATION);
    CHECK(s.raw[FC_SM_X] == 10 && s.raw[FC_SM_Y] == 20 && s.raw[FC_SM_Z] == 30);
    CHECK(s.raw[FC_SM_RX] == 0 && s.raw[FC_SM_RY] == 0 && s.raw[FC_SM_RZ] == 0);
    CHECK_NEAR(s.axes[FC_SM_X], 10.0 / 350, 1e-6);
    CHECK_CODE(DECODE(&s, 0x02, 0xf6, 0xff, 0xec, 0xff, 0xe2, 0xff), FC_SM_REPORT_ROTATION);
    CHECK(s.raw[FC_SM_RX] == -10 && s.raw[FC_SM_RY] == -20 && s.raw[FC_SM_RZ] == -30);
    /* the rotation report leaves the held translation alone */
    CHECK(s.raw[FC_SM_X] == 10 && s.raw[FC_SM_Z] == 30);
    CHECK_NEAR(s.axes[FC_SM_RZ], -30.0 / 350, 1e-6);
}

static void test_six_axis_and_clamp(void)
{
    fc_sm_state s;
    fc_sm_state_init(&s);
    /* 350, -350, 400, -400, 175, -175 */
    CHECK_CODE(DECODE(&s, 0x01, 0x5e, 0x01, 0xa2, 0xfe, 0x90, 0x01, 0x70, 0xfe, 0xaf, 0x00, 0x51, 0xff),
               FC_SM_REPORT_SIX_AXIS);
    const float want[6] = {1, -1, 1, -1, 0.5f, -0.5f};
    for (int i = 0; i < 6; i++)
        CHECK_NEAR(s.axes[i], want[i], 1e-6);
    CHECK(s.raw[FC_SM_Z] == 400 && s.raw[FC_SM_RX] == -400);
    /* extremes of int16 clamp too */
    CHECK_CODE(DECODE(&s, 0x01, 0x00, 0x80, 0xff, 0x7f, 0, 0, 0, 0, 0, 0, 0, 0), FC_SM_REPORT_SIX_AXIS);
    CHECK_NEAR(s.axes[0], -1, 0);
    CHECK_NEAR(s.axes[1], 1, 0);
    /* the zero report */
    CHECK_CODE(DECODE(&s, 0x01, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0), FC_SM_REPORT_SIX_AXIS);
    for (int i = 0; i < 6; i++)
        CHECK(s.axes[i] == 0.0f && s.raw[i] == 0);
}

static void test_short_and_unknown(void)
{
    fc_sm_state s;
    fc_sm_state_init(&s);
    DECODE(&s, 0x01, 10, 0, 20, 0, 30, 0);
    CHECK_CODE(DECODE(&s, 0x01, 1, 0, 2), FC_SM_REPORT_IGNORED);
    CHECK_CODE(DECODE(&s, 0x02, 1, 0, 2, 0, 3), FC_SM_REPORT_IGNORED);
    CHECK_CODE(DECODE(&s, 0x42, 1, 2, 3), FC_SM_REPORT_IGNORED);
    CHECK_CODE(fc_sm_decode(&s, (const uint8_t[]){0x03}, 1), FC_SM_REPORT_IGNORED);
    CHECK_CODE(fc_sm_decode(&s, NULL, 0), FC_SM_REPORT_IGNORED);
    CHECK(s.raw[FC_SM_X] == 10 && s.raw[FC_SM_Y] == 20);
    CHECK_CODE(DECODE(&s, 0x17, 87, 0), FC_SM_REPORT_BATTERY);
    CHECK(s.battery_percent == 87);
    CHECK(strcmp(fc_sm_report_kind_name(FC_SM_REPORT_SIX_AXIS), "six-axis") == 0);
    CHECK(fc_sm_report_is_motion(FC_SM_REPORT_ROTATION) && !fc_sm_report_is_motion(FC_SM_REPORT_BUTTONS));
}

static void test_button_bitmask_edges(void)
{
    fc_sm_state s;
    fc_sm_state_init(&s);
    CHECK_CODE(DECODE(&s, 0x03, 0x01, 0x00), FC_SM_REPORT_BUTTONS);
    CHECK(s.buttons == 1 && s.pressed == 1 && s.released == 0);
    DECODE(&s, 0x03, 0x03, 0x00);
    CHECK(s.buttons == 3 && s.pressed == 2 && s.released == 0);
    /* a motion report clears the edges but keeps the buttons */
    DECODE(&s, 0x01, 0, 0, 0, 0, 0, 0);
    CHECK(s.buttons == 3 && s.pressed == 0 && s.released == 0);
    DECODE(&s, 0x03, 0x02, 0x00);
    CHECK(s.buttons == 2 && s.pressed == 0 && s.released == 1);
    /* buttons beyond the first byte (SpacePilot Pro: 4 bytes) */
    DECODE(&s, 0x03, 0x00, 0x00, 0x00, 0x80);
    CHECK(s.buttons == 0x80000000u && s.pressed == 0x80000000u && s.released == 2);
    /* a repeated report is no new edge */
    DECODE(&s, 0x03, 0x00, 0x00, 0x00, 0x80);
    CHECK(s.pressed == 0 && s.released == 0);
}

static void test_button_array(void)
{
    fc_sm_state s;
    fc_sm_state_init(&s);
    DECODE(&s, 0x03, 0x01, 0x00);
    CHECK(s.buttons == 1);
    /* codes 2 and 13 held: buttons 1 and 12 */
    CHECK_CODE(DECODE(&s, 0x1c, 2, 0, 13, 0, 0, 0, 0, 0, 0, 0, 0, 0), FC_SM_REPORT_BUTTON_ARRAY);
    CHECK(s.button_array);
    CHECK_MSG(s.buttons == ((1u << 1) | (1u << 12)), "buttons 0x%x", s.buttons);
    CHECK(s.pressed == ((1u << 1) | (1u << 12)) && s.released == 1);
    /* once 0x1C was seen, report 3 is ignored */
    CHECK_CODE(DECODE(&s, 0x03, 0xff, 0xff), FC_SM_REPORT_IGNORED);
    CHECK(s.buttons == ((1u << 1) | (1u << 12)));
    /* codes out of range are dropped */
    DECODE(&s, 0x1c, 33, 0, 0xff, 0xff, 1, 0, 0, 0, 0, 0, 0, 0);
    CHECK(s.buttons == 1 && s.pressed == 1 && s.released == ((1u << 1) | (1u << 12)));
    DECODE(&s, 0x1c, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    CHECK(s.buttons == 0 && s.released == 1);
    /* long presses are their own bits and do not touch the buttons */
    CHECK_CODE(DECODE(&s, 0x1d, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0), FC_SM_REPORT_LONG_PRESS);
    CHECK(s.long_presses == 4 && s.buttons == 0);
}

static void test_device_table(void)
{
    CHECK(fc_sm_device_supported(0x256f, 0xc635));
    CHECK(fc_sm_device_supported(0x256f, 0xc652));
    CHECK(fc_sm_device_supported(0x256f, 0xc6ff));         /* unlisted 256f: accepted */
    CHECK(!fc_sm_device_supported(0x256f, 0xc650));        /* CadMouse */
    CHECK(!fc_sm_device_supported(0x256f, 0xc664));        /* keyboard */
    CHECK(fc_sm_device_supported(0x046d, 0xc626));
    CHECK(fc_sm_device_supported(0x046d, 0xc62b));
    CHECK(!fc_sm_device_supported(0x046d, 0xc52b));        /* a Logitech receiver */
    CHECK(!fc_sm_device_supported(0x046d, 0xc077));        /* a Logitech mouse */
    CHECK(!fc_sm_device_supported(0x1234, 0xc626));
    CHECK(strcmp(fc_sm_device_name(0x256f, 0xc635), "SpaceMouse Compact") == 0);
    CHECK(strcmp(fc_sm_device_name(0x046d, 0xc626), "SpaceNavigator") == 0);
    CHECK(fc_sm_vendor_count() == 2 && fc_sm_vendor(0) == 0x256f && fc_sm_vendor(1) == 0x046d);
}

int main(void)
{
    test_split_reports();
    test_six_axis_and_clamp();
    test_short_and_unknown();
    test_button_bitmask_edges();
    test_button_array();
    test_device_table();
    return test_result();
}
