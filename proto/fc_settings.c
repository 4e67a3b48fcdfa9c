/* fc_settings.c — default render settings and their domains. */
#include "fc_frame.h"

#include <math.h>

#include "fc_error.h"

#define MAX_RADIUS 1e6f
#define MAX_ITERATIONS 1000u
#define MAX_ABSORPTION 1e6f
#define MIN_IOR 1.0f
#define MAX_IOR 3.0f

void fc_settings_default(fc_settings *s)
{
    *s = (fc_settings){
        .radius = 0.0f,
        .smoothing = FC_SMOOTHING_CURVATURE,
        .iterations = 40,
        .fluid_color = {0.05f, 0.30f, 0.45f},
        .absorption = {2.5f, 0.9f, 0.45f},
        .ior = 1.33f,
    };
}

/* NaN fails both comparisons, so this also rejects non-finite values. */
static bool in_range(float v, float lo, float hi)
{
    return v >= lo && v <= hi;
}

fc_code fc_settings_validate(const fc_settings *s, fc_error *err)
{
    if (!in_range(s->radius, 0.0f, MAX_RADIUS))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "radius %g is outside [0, %g]", (double)s->radius,
                            (double)MAX_RADIUS);
    if (s->smoothing != FC_SMOOTHING_NONE && s->smoothing != FC_SMOOTHING_CURVATURE)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown smoothing %u", (unsigned)s->smoothing);
    if (s->iterations > MAX_ITERATIONS)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "iterations %u exceed %u", s->iterations, MAX_ITERATIONS);
    for (int c = 0; c < 3; c++) {
        if (!in_range(s->fluid_color[c], 0.0f, 1.0f))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "fluid_color[%d] %g is outside [0, 1]", c,
                                (double)s->fluid_color[c]);
        if (!in_range(s->absorption[c], 0.0f, MAX_ABSORPTION))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "absorption[%d] %g is outside [0, %g]", c,
                                (double)s->absorption[c], (double)MAX_ABSORPTION);
    }
    if (!in_range(s->ior, MIN_IOR, MAX_IOR))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "ior %g is outside [%g, %g]", (double)s->ior,
                            (double)MIN_IOR, (double)MAX_IOR);
    return FC_OK;
}
