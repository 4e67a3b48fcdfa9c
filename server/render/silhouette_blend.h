/* silhouette_blend.h — the last step of reduced-resolution smoothing (van der
 * Laan et al. 2009, §3.5.1): the shaded colour, not depth or normals, is
 * blended bilinearly over the pixels whose smoothing texels straddle a
 * silhouette (silhouette_blend.frag.glsl). */
#ifndef FC_SILHOUETTE_BLEND_H
#define FC_SILHOUETTE_BLEND_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "render_target.h"

typedef struct fc_silhouette_blend {
    GLuint program;
    GLuint empty_vertex_array;
    fc_render_target srgb_target;    /* GL_SRGB8_ALPHA8, for an 8-bit composite */
    fc_render_target float_target;   /* GL_RGBA32F, for a float composite */
} fc_silhouette_blend;

fc_code fc_silhouette_blend_create(const char *shader_dir, fc_silhouette_blend *sb, fc_error *err);
void fc_silhouette_blend_destroy(fc_silhouette_blend *sb);

/* Blends `shaded` (the full-resolution composite, sRGB 8-bit when want_u8,
 * else float) over the silhouettes of `low_depth` (smoothed depth with `block`
 * image pixels per texel) into the target of the same kind; *result points at it. */
fc_code fc_silhouette_blend_run(fc_silhouette_blend *sb, const fc_render_target *shaded,
                                const fc_render_target *low_depth, uint32_t block, float depth_jump, bool want_u8,
                                const fc_render_target **result, fc_error *err);

#endif
