/* surface_extract.h — isosurface extraction on the GPU (issue 27; Janisz
 * section 4.2): the particles of a frame -> a scalar field sampled on a sparse
 * set of blocks near them -> marching cubes -> welded, indexed triangles with
 * normals from the field's gradient and the particles' attributes interpolated
 * to the vertices. */
#ifndef FC_SURFACE_EXTRACT_H
#define FC_SURFACE_EXTRACT_H

#include "fc_surface_mesh.h"
#include "fluidcast_types.h"
#include "pipeline.h"

/* Extracts the surface of `frame` with the surface settings of `settings` (cell size, kernel, smoothing) on
 * the pipeline's GL context. Deterministic; bounded memory (LIMIT error past the grid budget). */
fc_code fc_surface_extract(fc_pipeline *pipeline, const fc_frame *frame, const fc_settings *settings,
                           fc_surface_mesh *out, fc_error *error);

#endif
