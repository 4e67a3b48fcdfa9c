/* spacemouse_filter.c — held deflection, watchdog and per-axis shaping. */
#include "spacemouse_filter.h"

#include <math.h>
#include <string.h>

#include "fc_error.h"

static const char *const axis_names[FC_SM_AXES] = {"X", "Y", "Z", "RX", "RY", "RZ"};

void fc_sm_filter_config_default(fc_sm_filter_config *c)
{
    memset(c, 0, sizeof *c);
    for (int i = 0; i < FC_SM_AXES; i++) {
        c->source[i] = (uint8_t)i;
        c->sign[i] = 1;
        c->dead_zone[i] = 2.0f / FC_SM_RAW_RANGE;
        c->sensitivity[i] = 1.0f;
    }
    c->watchdog_ns = FC_SM_WATCHDOG_NS_DEFAULT;
}

fc_code fc_sm_filter_config_validate(const fc_sm_filter_config *c, fc_error *err)
{
    for (int i = 0; i < FC_SM_AXES; i++) {
        if (c->source[i] >= FC_SM_AXES)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "axis %s: source %u is not an axis 0..5",
                                axis_names[i], c->source[i]);
        if (c->sign[i] != 1 && c->sign[i] != -1)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "axis %s: sign %d is not +1 or -1",
                                axis_names[i], c->sign[i]);
        if (!(c->dead_zone[i] >= 0.0f && c->dead_zone[i] < 1.0f))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "axis %s: dead zone %g is outside [0, 1)",
                                axis_names[i], (double)c->dead_zone[i]);
        if (!isfinite(c->sensitivity[i]))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "axis %s: sensitivity is not finite",
                                axis_names[i]);
    }
    return FC_OK;
}

void fc_sm_filter_init(fc_sm_filter *f, const fc_sm_filter_config *config)
{
    memset(f, 0, sizeof *f);
    f->config = *config;
}

void fc_sm_filter_motion(fc_sm_filter *f, const fc_sm_state *state, uint64_t now_ns)
{
    memcpy(f->held, state->axes, sizeof f->held);
    f->last_motion_ns = now_ns;
    f->has_motion = true;
}

static bool watchdog_expired(const fc_sm_filter *f, uint64_t now_ns)
{
    if (!f->has_motion)
        return true;
    if (f->config.watchdog_ns == 0)
        return false;
    /* A report stamped after now (clock read in another order) is fresh. */
    return now_ns > f->last_motion_ns && now_ns - f->last_motion_ns > f->config.watchdog_ns;
}

/* |v| <= dz reads 0; beyond, the remaining range maps onto (0, 1]. */
static float apply_dead_zone(float v, float dz)
{
    float m = fabsf(v);
    if (m <= dz)
        return 0.0f;
    return copysignf((m - dz) / (1.0f - dz), v);
}

static void keep_dominant(float v[FC_SM_AXES])
{
    int best = 0;
    for (int i = 1; i < FC_SM_AXES; i++)
        if (fabsf(v[i]) > fabsf(v[best]))
            best = i;
    for (int i = 0; i < FC_SM_AXES; i++)
        if (i != best)
            v[i] = 0.0f;
}

void fc_sm_filter_output(const fc_sm_filter *f, uint64_t now_ns, float out[FC_SM_AXES])
{
    const fc_sm_filter_config *c = &f->config;
    if (watchdog_expired(f, now_ns)) {
        memset(out, 0, sizeof(float) * FC_SM_AXES);
        return;
    }
    for (int i = 0; i < FC_SM_AXES; i++)
        out[i] = apply_dead_zone((float)c->sign[i] * f->held[c->source[i]], c->dead_zone[i]);
    if (c->dominant_axis)
        keep_dominant(out);
    for (int i = 0; i < FC_SM_AXES; i++)
        out[i] *= c->sensitivity[i];
}
