/* thickness_filter.h — a separable Gaussian blur of the thickness (Janisz
 * 2012, §4.1.3) that also brings thickness computed at reduced resolution
 * back to the full image size. */
#ifndef FC_THICKNESS_FILTER_H
#define FC_THICKNESS_FILTER_H

#include <epoxy/gl.h>

#include "render_target.h"

typedef struct fc_thickness_filter {
    GLuint program;
    GLuint empty_vertex_array;
    fc_render_target across;   /* R32F, blurred along x, at the source's resolution */
    fc_render_target result;   /* R32F, blurred along both axes, at the output resolution */
} fc_thickness_filter;

fc_code fc_thickness_filter_create(const char *shader_dir, fc_thickness_filter *f, fc_error *err);
void fc_thickness_filter_destroy(fc_thickness_filter *f);

/* Blurs `source` (bilinear R32F) with a Gaussian of standard deviation
 * `sigma` source texels (0 = none) into a width x height image; *result is
 * f->result. The kernel is normalised, so thickness is conserved. */
fc_code fc_thickness_filter_run(fc_thickness_filter *f, const fc_render_target *source, float sigma,
                                uint32_t width, uint32_t height, const fc_render_target **result, fc_error *err);

#endif
