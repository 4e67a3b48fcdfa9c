/* resolution_scale.h — depth smoothing at a fraction of the image's
 * resolution (van der Laan et al. 2009, §3.5.1): the depth goes down to the
 * smoothing grid with the nearest-surface rule and comes back up
 * surface-aware; the colour blend over silhouettes is silhouette_blend.h. */
#ifndef FC_RESOLUTION_SCALE_H
#define FC_RESOLUTION_SCALE_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "render_target.h"

typedef struct fc_resolution_scale {
    GLuint downsample_program;
    GLuint upsample_program;
    GLuint empty_vertex_array;
    fc_render_target low;    /* R32F depth on the smoothing grid */
    fc_render_target full;   /* R32F depth back at the image's resolution */
} fc_resolution_scale;

fc_code fc_resolution_scale_create(const char *shader_dir, fc_resolution_scale *rs, fc_error *err);
void fc_resolution_scale_destroy(fc_resolution_scale *rs);

/* Image pixels per smoothing texel along each axis for a smooth_scale:
 * 1 for 1 (and for 0, "not set"), 2 for 0.5, 4 for 0.25. */
uint32_t fc_resolution_scale_block(float smooth_scale);

/* Each texel of rs->low (ceil(size / block) texels per axis) gets the nearest
 * fluid depth of its block of `depth`; *low points at it. */
fc_code fc_resolution_scale_down(fc_resolution_scale *rs, const fc_render_target *depth, uint32_t block,
                                 const fc_render_target **low, fc_error *err);

/* `smoothed` (on the grid of fc_resolution_scale_down) back at the size of
 * `depth`, the unsmoothed depth it came from, which decides the surface of
 * each pixel where texels differ; into rs->full, *full pointing at it.
 * Neighbours further apart in depth than depth_jump are separate surfaces. */
fc_code fc_resolution_scale_up(fc_resolution_scale *rs, const fc_render_target *smoothed,
                               const fc_render_target *depth, uint32_t block, float depth_jump,
                               const fc_render_target **full, fc_error *err);

#endif
