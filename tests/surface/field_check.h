/* field_check.h — the surface field's kernel in double, written apart from
 * surface_kernel.comp.glsl's weight() so the surface tests check the shaders
 * against an independent sum. */
#ifndef FC_FIELD_CHECK_H
#define FC_FIELD_CHECK_H

#include "fluidcast_types.h"

/* One particle's weight at distance d for particles of `radius`: the
 * metaball (1 - d^2 / R^2)^3 or the cubic spline, R the kernel's reach
 * (fc_surface_kernel_reach_radii radii); 0 from R on. */
double field_check_weight(fc_surface_kernel kernel, double radius, double d);

#endif
