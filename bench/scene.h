/* scene.h — deterministic synthetic particle scenes for benchmarks: SPH-like
 * jittered lattices with a known spacing, at any particle count. */
#ifndef FC_BENCH_SCENE_H
#define FC_BENCH_SCENE_H

#include "fluidcast_types.h"

/* Sphere radius per lattice spacing the benchmark renders with (and hands to
 * peer renderers): the factor fc_frame_estimate_radius applies to the
 * nearest-neighbour distance, so spheres overlap and close the surface. */
#define BENCH_SCENE_RADIUS_PER_SPACING 0.9f

/* A sphere of fluid (radius 0.3, centre (0,0,0.6)) above a 2 x 2 x 0.12 pool on
 * z = 0, with exactly `count` particles; +z up, metres.
 * Returns the lattice spacing through *spacing. */
fc_code bench_scene_drop(uint64_t count, fc_frame *frame, float *spacing, fc_error *err);

/* The camera the sample data suggests for the drop scene. */
void bench_scene_drop_camera(uint32_t width, uint32_t height, fc_camera *cam);

#endif
