/* thickness_filter.h — a separable Gaussian blur of the thickness (Janisz
 * 2012, §4.1.3) that also resamples it: the first of its two passes reads
 * the splat at any resolution and writes the blur's resolution (half the
 * image's, or the splat's where that is lower), so the second pass and the
 * composite's bilinear lookup work on a quarter of the pixels. */
#ifndef FC_THICKNESS_FILTER_H
#define FC_THICKNESS_FILTER_H

#include <epoxy/gl.h>

#include "render_target.h"

typedef struct fc_thickness_filter {
    GLuint program;
    GLuint empty_vertex_array;
    /* R32F (RGBA32F for the filter of fc_thickness_filter_create_color) */
    fc_render_target across;      /* R32F, resampled and blurred along x, at the blur's resolution */
    fc_render_target result;      /* R32F, blurred along both axes, at the blur's resolution */
    fc_render_target upsampled;   /* R32F, at the image's size: only for the thickness AOV */
} fc_thickness_filter;

fc_code fc_thickness_filter_create(const char *shader_dir, fc_thickness_filter *f, fc_error *err);
/* The same filter for the thickness with its colour (RGBA32F: thickness, then
 * colour x thickness; thickness_color.frag.glsl), every channel blurred alike. */
fc_code fc_thickness_filter_create_color(const char *shader_dir, fc_thickness_filter *f, fc_error *err);
void fc_thickness_filter_destroy(fc_thickness_filter *f);

/* Resamples `source` (bilinear R32F) to width x height, averaging the source
 * texels under each target pixel where it is smaller, and blurs it with a
 * Gaussian of standard deviation `sigma` target pixels (0 = none), cut off at
 * three. *result is f->result, or `source` itself when there is nothing to
 * do. The kernel is normalised, so thickness is conserved. */
fc_code fc_thickness_filter_run(fc_thickness_filter *f, const fc_render_target *source, float sigma,
                                uint32_t width, uint32_t height, const fc_render_target **result, fc_error *err);

/* Bilinear resampling of `source` to width x height in f->upsampled: what the
 * composite sees, as an image of the view's size. */
fc_code fc_thickness_filter_upsample(fc_thickness_filter *f, const fc_render_target *source, uint32_t width,
                                     uint32_t height, const fc_render_target **result, fc_error *err);

#endif
