/* surface_extract.c — fc_surface_extract (surface_extract.h): the pipeline's
 * surface passes and, for the anisotropic kernel, its ellipsoids of the
 * frame, handed to the mesher (surface_mesher.c). */
#include "surface_extract.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "pipeline_internal.h"
#include "surface_mesher.h"

fc_code fc_surface_extract(fc_pipeline *pipeline, const fc_frame *frame, const fc_settings *settings,
                           fc_surface_mesh *out, fc_error *error)
{
    memset(out, 0, sizeof *out);
    fc_code code = fc_surface_mesher_check(frame, settings, error);
    const fc_surface_passes *passes = NULL;
    if (code == FC_OK && frame->count > 0)
        code = fc_pipeline_surface_passes(pipeline, &passes, error);
    if (code != FC_OK || frame->count == 0)
        return code;
    fc_ellipsoid *ellipsoids = NULL;
    if (settings->surface_kernel == FC_SURFACE_KERNEL_ANISOTROPIC) {
        ellipsoids = malloc((size_t)frame->count * sizeof *ellipsoids);
        code = ellipsoids ? fc_pipeline_frame_ellipsoids(pipeline, frame, ellipsoids, error)
                          : fc_error_set(error, FC_ERR_NOMEM, "cannot allocate %llu ellipsoids",
                                         (unsigned long long)frame->count);
    }
    if (code == FC_OK)
        code = fc_surface_mesher_run(passes, frame, ellipsoids, settings, out, error);
    free(ellipsoids);
    return code;
}
