/* surface_mesher.h — the surface mesh of a frame on the GPU, from the passes
 * and (for the anisotropic kernel) the ellipsoids it is given: the work of
 * fc_surface_extract (surface_extract.h) and of the pipeline's --surface
 * mesh renders, which own those inputs. */
#ifndef FC_SURFACE_MESHER_H
#define FC_SURFACE_MESHER_H

#include "anisotropy.h"
#include "fc_surface_mesh.h"
#include "fluidcast_types.h"
#include "surface_grid.h"
#include "surface_passes.h"

/* How far a particle's field reaches, in its radii (its ellipsoid's longest
 * axis for the anisotropic kernel): the metaballs' radius of influence
 * (Janisz's R_c > R) and the cubic spline's support 2 h, with h = 2 r (the
 * smoothing length splashsurf meshes with by default). The iso value is a
 * lone particle's field at one radius, so a lone particle meshes as its
 * sphere. The reaches are wide enough that particles at rest, 2 r apart as
 * solvers write them (r: half the spacing), fill the space between them even
 * jittered: at a lattice cube's centre the field is 3.4 (metaball) and 4.6
 * (spline) times the iso value, where a reach of 2 r, used until 2026-12-05,
 * gave 0.3 and 0.16 and left a bubble in every cube (a sponge of triangles
 * through the whole volume). The mesh lies within the reach. */
#define FC_SURFACE_METABALL_REACH_RADII 3.0f
#define FC_SURFACE_SPH_REACH_RADII 4.0f
#define FC_SURFACE_KERNEL_MAX_REACH_RADII FC_SURFACE_SPH_REACH_RADII

/* The reach of `kernel`'s field in particle radii (the anisotropic kernel is
 * the metaballs' on ellipsoids). */
float fc_surface_kernel_reach_radii(fc_surface_kernel kernel);

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

/* The field pass alone (tests/surface/test_surface_solid.c checks what it
 * proves): the grid of a frame (metaball or sph kernel) and the field at every
 * sample of each of its blocks, FC_SURFACE_BLOCK_SAMPLES a block in key order,
 * malloc'd, with the iso value; a solid block's samples hold the iso value
 * itself (surface_field.comp.glsl). The caller frees the grid and the field. */
fc_code fc_surface_mesher_field(const fc_surface_passes *passes, const fc_frame *frame, const fc_settings *settings,
                                fc_surface_grid *grid, float **field, float *iso, fc_error *err);

#endif
