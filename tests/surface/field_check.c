/* field_check.c — the kernel of field_check.h. */
#include "field_check.h"

#include "surface_mesher.h"

double field_check_weight(fc_surface_kernel kernel, double radius, double d)
{
    double reach = fc_surface_kernel_reach_radii(kernel) * radius;
    if (d >= reach)
        return 0.0;
    if (kernel == FC_SURFACE_KERNEL_METABALL) {
        double q = 1.0 - d * d / (reach * reach);
        return q * q * q;
    }
    double q = d / (0.5 * reach);
    return q < 1.0 ? 1.0 - 1.5 * q * q + 0.75 * q * q * q : 0.25 * (2.0 - q) * (2.0 - q) * (2.0 - q);
}
