/* test_spacemouse_filter.c — the filter driven by an injected clock: held
 * deflection and the watchdog, dead zone, sign, remap, sensitivity and the
 * dominant-axis mode. */
#include <string.h>

#include "spacemouse_filter.h"
#include "test_util.h"

#define MS 1000000ull

static fc_sm_state state_of(float x, float y, float z, float rx, float ry, float rz)
{
    fc_sm_state s;
    fc_sm_state_init(&s);
    const float v[6] = {x, y, z, rx, ry, rz};
    memcpy(s.axes, v, sizeof v);
    return s;
}

static void no_dead_zone(fc_sm_filter_config *c)
{
    for (int i = 0; i < FC_SM_AXES; i++)
        c->dead_zone[i] = 0.0f;
}

static void test_watchdog(void)
{
    fc_sm_filter_config c;
    fc_sm_filter_config_default(&c);
    CHECK(c.watchdog_ns == 200 * MS);
    fc_sm_filter f;
    fc_sm_filter_init(&f, &c);
    float out[6];
    fc_sm_filter_output(&f, 1000 * MS, out);
    CHECK(out[0] == 0.0f);                     /* nothing reported yet */
    fc_sm_state s = state_of(0.5f, 0, 0, 0, 0, 0);
    fc_sm_filter_motion(&f, &s, 1000 * MS);
    fc_sm_filter_output(&f, 1000 * MS, out);
    CHECK_NEAR(out[0], (0.5 - 2.0 / 350) / (1 - 2.0 / 350), 1e-6);
    fc_sm_filter_output(&f, 1200 * MS, out);   /* exactly 200 ms: still held */
    CHECK(out[0] > 0.49f);
    fc_sm_filter_output(&f, 1200 * MS + 1, out);
    CHECK(out[0] == 0.0f);                     /* past the watchdog: zero */
    /* a fresh report revives it; a clock read before the report's time is fresh */
    fc_sm_filter_motion(&f, &s, 1300 * MS);
    fc_sm_filter_output(&f, 1299 * MS, out);
    CHECK(out[0] > 0.49f);
    /* the zero report zeroes at once */
    fc_sm_state zero = state_of(0, 0, 0, 0, 0, 0);
    fc_sm_filter_motion(&f, &zero, 1310 * MS);
    fc_sm_filter_output(&f, 1310 * MS, out);
    CHECK(out[0] == 0.0f);
    /* watchdog 0: held forever */
    c.watchdog_ns = 0;
    fc_sm_filter_init(&f, &c);
    fc_sm_filter_motion(&f, &s, 0);
    fc_sm_filter_output(&f, 3600000 * MS, out);
    CHECK(out[0] > 0.49f);
}

static void test_dead_zone(void)
{
    fc_sm_filter_config c;
    fc_sm_filter_config_default(&c);
    c.dead_zone[FC_SM_X] = 0.1f;
    fc_sm_filter f;
    fc_sm_filter_init(&f, &c);
    float out[6];
    fc_sm_state s = state_of(0.1f, 2.0f / 350, 3.0f / 350, -0.55f, 1.0f, -1.0f);
    fc_sm_filter_motion(&f, &s, 0);
    fc_sm_filter_output(&f, 0, out);
    CHECK(out[FC_SM_X] == 0.0f);               /* at the dead zone's edge */
    CHECK(out[FC_SM_Y] == 0.0f);               /* 2 raw units: spacenavd's default */
    CHECK(out[FC_SM_Z] > 0.0f && out[FC_SM_Z] < 1.5f / 350);   /* continuous past it */
    CHECK_NEAR(out[FC_SM_RY], 1.0, 1e-6);      /* full deflection stays full */
    CHECK_NEAR(out[FC_SM_RZ], -1.0, 1e-6);
    s.axes[FC_SM_X] = 0.55f;
    fc_sm_filter_motion(&f, &s, 0);
    fc_sm_filter_output(&f, 0, out);
    CHECK_NEAR(out[FC_SM_X], 0.5, 1e-6);       /* (0.55 - 0.1) / 0.9 */
}

static void test_sign_remap_sensitivity(void)
{
    fc_sm_filter_config c;
    fc_sm_filter_config_default(&c);
    no_dead_zone(&c);
    c.source[FC_SM_X] = FC_SM_Z;               /* swap X and Z */
    c.source[FC_SM_Z] = FC_SM_X;
    c.sign[FC_SM_Y] = -1;
    c.sensitivity[FC_SM_RX] = 2.5f;
    c.sensitivity[FC_SM_RY] = 0.0f;            /* an axis switched off */
    fc_error err;
    CHECK_CODE(fc_sm_filter_config_validate(&c, &err), FC_OK);
    fc_sm_filter f;
    fc_sm_filter_init(&f, &c);
    fc_sm_state s = state_of(0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f);
    fc_sm_filter_motion(&f, &s, 0);
    float out[6];
    fc_sm_filter_output(&f, 0, out);
    CHECK_NEAR(out[FC_SM_X], 0.3, 1e-6);
    CHECK_NEAR(out[FC_SM_Y], -0.2, 1e-6);
    CHECK_NEAR(out[FC_SM_Z], 0.1, 1e-6);
    CHECK_NEAR(out[FC_SM_RX], 1.0, 1e-6);
    CHECK(out[FC_SM_RY] == 0.0f);
    CHECK_NEAR(out[FC_SM_RZ], 0.6, 1e-6);
}

static void test_dominant_axis(void)
{
    fc_sm_filter_config c;
    fc_sm_filter_config_default(&c);
    no_dead_zone(&c);
    c.dominant_axis = true;
    c.sensitivity[FC_SM_RY] = 10.0f;           /* sensitivity does not pick the winner */
    fc_sm_filter f;
    fc_sm_filter_init(&f, &c);
    fc_sm_state s = state_of(0.2f, -0.7f, 0.3f, 0.1f, 0.5f, 0.0f);
    fc_sm_filter_motion(&f, &s, 0);
    float out[6];
    fc_sm_filter_output(&f, 0, out);
    for (int i = 0; i < 6; i++)
        CHECK_MSG(i == FC_SM_Y ? out[i] == -0.7f : out[i] == 0.0f, "axis %d = %g", i, (double)out[i]);
    /* rotation can dominate */
    s = state_of(0.2f, 0.1f, 0.0f, 0.0f, 0.0f, -0.9f);
    fc_sm_filter_motion(&f, &s, 0);
    fc_sm_filter_output(&f, 0, out);
    CHECK(out[FC_SM_RZ] == -0.9f && out[FC_SM_X] == 0.0f);
}

static void test_validate(void)
{
    fc_sm_filter_config c;
    fc_sm_filter_config_default(&c);
    fc_error err;
    c.source[2] = 6;
    CHECK_CODE(fc_sm_filter_config_validate(&c, &err), FC_ERR_INVALID_VALUE);
    CHECK(strstr(err.message, "axis Z") != NULL);
    fc_sm_filter_config_default(&c);
    c.sign[4] = 0;
    CHECK_CODE(fc_sm_filter_config_validate(&c, &err), FC_ERR_INVALID_VALUE);
    fc_sm_filter_config_default(&c);
    c.dead_zone[0] = 1.0f;
    CHECK_CODE(fc_sm_filter_config_validate(&c, &err), FC_ERR_INVALID_VALUE);
    fc_sm_filter_config_default(&c);
    c.sensitivity[5] = 1.0f / 0.0f;
    CHECK_CODE(fc_sm_filter_config_validate(&c, &err), FC_ERR_INVALID_VALUE);
}

int main(void)
{
    test_watchdog();
    test_dead_zone();
    test_sign_remap_sensitivity();
    test_dominant_axis();
    test_validate();
    return test_result();
}
