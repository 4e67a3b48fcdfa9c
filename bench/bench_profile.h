/* bench_profile.h — fluidcast-bench --profile: where a configuration's frame
 * time goes, pass by pass (fc_pipeline_set_profiling), with the fragment
 * counts of each pass and the sizes of the particles' sprites in pixels. */
#ifndef FC_BENCH_PROFILE_H
#define FC_BENCH_PROFILE_H

#include "fluidcast_types.h"
#include "pipeline.h"

/* Projected sphere diameters in pixels of the frame's particles seen by
 * `cam` (min, median, max over the particles in front of the camera). */
void bench_sprite_diameters(const fc_frame *frame, const fc_camera *cam, float radius, float out[3]);

/* Renders `frames` profiled frames of the uploaded particles and prints a
 * markdown table with the median wall time and fragment count of each pass;
 * `particles` and `sprite_px` (bench_sprite_diameters) go into its title. */
fc_code bench_profile_config(fc_pipeline *pipe, int frames, const fc_camera *cam, const fc_settings *settings,
                             uint64_t particles, const float sprite_px[3], fc_error *err);

/* Times the anisotropy passes (anisotropy.h) on the particles of `frame`
 * for spheres of `radius`: `frames` times, each after a fresh upload (which
 * invalidates the ellipsoids), a tiny profiled render whose "anisotropy" pass
 * is the computation alone; prints the median. */
fc_code bench_profile_anisotropy(fc_pipeline *pipe, const fc_frame *frame, float radius, int frames,
                                 fc_error *err);

#endif
