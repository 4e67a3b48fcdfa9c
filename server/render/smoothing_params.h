/* smoothing_params.h — what a depth smoothing method needs to know about a
 * request, shared by the smoother and every method module. */
#ifndef FC_SMOOTHING_PARAMS_H
#define FC_SMOOTHING_PARAMS_H

#include <stdint.h>

#include "fluidcast_types.h"
#include "pass_profile.h"

/* fc_smoother_run takes pixel sizes for the image; the method modules get a
 * copy converted to the grid they smooth (coarser at a smooth_scale < 1). */
typedef struct fc_smoothing_params {
    fc_smoothing method;
    uint32_t iterations;      /* curvature-flow steps, or x+y filter passes */
    float pixel_scale[2];     /* (Cx, Cy), see fc_view_pixel_scale */
    float depth_jump;         /* world units: neighbours further apart in depth are separate surfaces */
    float particle_radius;    /* world units */
    uint32_t filter_radius;   /* kernel half-width in pixels; 0 = from the projected particle size */
    float reference_depth;    /* typical depth of the fluid, for a method with one kernel for the image */
    float smooth_scale;       /* resolution of smoothing: 1, 0.5 or 0.25 of the image (0 = 1) */
    fc_pass_profile *profile; /* records the resampling and the method; NULL: none */
} fc_smoothing_params;

#endif
