/* surface_mesher.h — the surface mesh of a frame on the GPU, from the passes
 * and (for the anisotropic kernel) the ellipsoids it is given: the work of
 * fc_surface_extract (surface_extract.h) and of the pipeline's --surface
 * mesh renders, which own those inputs. */
#ifndef FC_SURFACE_MESHER_H
#define FC_SURFACE_MESHER_H

#include "anisotropy.h"
#include "fc_surface_mesh.h"
#include "fluidcast_types.h"
#include "surface_passes.h"

/* How far a particle's field reaches, in its radii (its ellipsoid's longest
 * axis for the anisotropic kernel): the metaball's radius of influence and
 * the cubic spline's support. The mesh lies within it. */
#define FC_SURFACE_KERNEL_REACH_RADII 2.0f

/* Checks what the mesher takes before anything is read or computed: at most
 * FC_SURFACE_MAX_PARTICLES (LIMIT, the arrays untouched), valid settings and
 * a valid frame (INVALID_VALUE: NaN, radii out of range). */
fc_code fc_surface_mesher_check(const fc_frame *frame, const fc_settings *settings, fc_error *err);

/* The mesh of a checked frame with the surface settings (cell, kernel,
 * smoothing; the radius rule of fc_radius_source_of). `ellipsoids` (count of
 * them, frame order) only for the anisotropic kernel, else ignored. A frame
 * of no particles gives the empty mesh. On failure *out is empty. */
fc_code fc_surface_mesher_run(const fc_surface_passes *passes, const fc_frame *frame, const fc_ellipsoid *ellipsoids,
                              const fc_settings *settings, fc_surface_mesh *out, fc_error *err);

#endif
