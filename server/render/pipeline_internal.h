/* pipeline_internal.h — what the modules that implement parts of pipeline.h
 * (the foam state) reach for inside a pipeline. Not part of the public API. */
#ifndef FC_PIPELINE_INTERNAL_H
#define FC_PIPELINE_INTERNAL_H

#include "anisotropy.h"
#include "depth_pass.h"
#include "particle_attributes.h"
#include "pipeline.h"
#include "shadow_pass.h"
#include "surface_passes.h"

/* The per-particle records of the uploaded frame. */
fc_particle_attributes *fc_pipeline_particle_attributes(fc_pipeline *p);

/* The ellipsoids of the last render with the anisotropic kernel (read them
 * with fc_anisotropy_read; tests). */
const fc_anisotropy *fc_pipeline_anisotropy(const fc_pipeline *p);

/* Uploads `frame` (as fc_pipeline_upload: it becomes the pipeline's frame,
 * in its own order) and reads its particles' ellipsoids into out (count of
 * them, frame order): the surface mesh's anisotropic kernel. */
fc_code fc_pipeline_frame_ellipsoids(fc_pipeline *p, const fc_frame *frame, fc_ellipsoid *out, fc_error *err);

/* The surface mesh passes (surface_extract.c), built on their first use. */
fc_code fc_pipeline_surface_passes(fc_pipeline *p, const fc_surface_passes **out, fc_error *err);

/* Forces the surface splat of every render from now on (FC_SPLAT_AUTO
 * restores the choice by sprite size); for tests and the benchmark. */
void fc_pipeline_force_splat(fc_pipeline *p, fc_splat_method method);

/* The splat the last render used: FC_SPLAT_FRAGMENT or FC_SPLAT_COMPUTE. */
fc_splat_method fc_pipeline_last_splat(const fc_pipeline *p);

/* How the compute splat walked each particle's pixels when it last ran. */
fc_splat_walk fc_pipeline_last_splat_walk(const fc_pipeline *p);

/* The camera's compute splat: its culling switch and tiles (tests). */
fc_compute_splat *fc_pipeline_compute_splat(fc_pipeline *p);

/* The sun's shadow pass: its map, the fluid's depth from the sun, its splat
 * (whose method a test may force); tests. */
fc_shadow_pass *fc_pipeline_shadow_pass(fc_pipeline *p);

/* Whether the background pass lays down the composite's mask (the driver has
 * ARB_shader_stencil_export) rather than the composite's own mask pass; tests. */
bool fc_pipeline_background_writes_mask(const fc_pipeline *p);

/* Whether the background and composite programs take their uniforms as flat
 * inputs (flat_constants.h, fc_pipeline_config.constants); tests. */
bool fc_pipeline_flat_constants(const fc_pipeline *p);

#endif
