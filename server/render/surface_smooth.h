/* surface_smooth.h — Taubin's smoothing of a surface mesh (Taubin 1995,
 * "A signal processing approach to fair surface design"): each step a
 * Laplacian step that shrinks (lambda) and one that inflates (mu, slightly
 * larger and negative), which smooths the triangles' noise without the
 * shrinking of plain Laplacian smoothing, so the volume stays. */
#ifndef FC_SURFACE_SMOOTH_H
#define FC_SURFACE_SMOOTH_H

#include "fc_surface_mesh.h"
#include "fluidcast_types.h"

#define FC_TAUBIN_LAMBDA 0.5f
#define FC_TAUBIN_MU (-0.53f)

/* Moves the mesh's vertices by `steps` Taubin steps (uniform weights over
 * each vertex's neighbours); the triangles, normals and attributes stay.
 * NOMEM when the neighbour lists cannot be allocated. */
fc_code fc_surface_smooth(fc_surface_mesh *mesh, uint32_t steps, fc_error *err);

#endif
