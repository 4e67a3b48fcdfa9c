/* separable_filter.h — a depth filter applied as 1-D passes along x, then y,
 * ping-ponging between two targets: the shape shared by the bilateral,
 * narrow-range and binomial smoothing (their shaders link
 * depth_filter_common.glsl, whose uniforms are set here). A filter is a
 * fragment shader drawn over the target, or a compute shader writing the
 * target's texture as an image. */
#ifndef FC_SEPARABLE_FILTER_H
#define FC_SEPARABLE_FILTER_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "render_target.h"
#include "smoothing_params.h"

#define FC_FILTER_UNIFORMS 8
/* A compute filter's invocation filters this many consecutive pixels along
 * the axis (RUN of the *.comp.glsl filters). */
#define FC_FILTER_RUN 8u

typedef struct fc_separable_filter {
    GLuint program;
    GLint uniform[FC_FILTER_UNIFORMS];   /* locations of the common uniforms, -1 where unused */
    GLuint empty_vertex_array;
    GLint group_size[2];             /* compute: invocations of a workgroup in x and y; 0: fragment */
    float radii_per_kernel;          /* automatic half-width, in projected particle radii */
    fc_render_target ping_pong[2];   /* of the format the shader writes, sized to the input */
    uint32_t passes_since_begin;     /* the first two write every pixel of both targets */
} fc_separable_filter;

/* Links depth_filter_common.glsl and `shader_file` into a filter writing
 * `color_format`: with fullscreen.vert.glsl for a *.frag.glsl; a *.comp.glsl
 * lays its invocations over the image, each filtering FC_FILTER_RUN pixels
 * along the axis, and writes image unit 0. */
fc_code fc_separable_filter_create(const char *shader_dir, const char *shader_file, GLenum color_format,
                                   float radii_per_kernel, fc_separable_filter *f, fc_error *err);
void fc_separable_filter_destroy(fc_separable_filter *f);

/* Sizes the targets to `depth`, binds the program and sets the common uniforms
 * from `grid` (parameters in the pixels of the grid being filtered); the
 * caller may then set its own uniforms and run passes. */
fc_code fc_separable_filter_begin(fc_separable_filter *f, const fc_render_target *depth,
                                  const fc_smoothing_params *grid, fc_error *err);

/* One 1-D pass along `axis` (0 = x, 1 = y) from `source` into the ping-pong
 * target that is not `source`; returns that target. A filter may leave the
 * background (depth 0, which every pass keeps at exactly 0) unwritten from
 * the third pass after begin on: by then both targets hold this run's
 * background (the shader's `store_background`, false from then on). */
const fc_render_target *fc_separable_filter_pass(fc_separable_filter *f, const fc_render_target *source, int axis);

/* begin, then grid->iterations pairs of x and y passes; *result is the last
 * target written (`depth` itself for no iterations). */
fc_code fc_separable_filter_run(fc_separable_filter *f, const fc_render_target *depth,
                                const fc_smoothing_params *grid, const fc_render_target **result, fc_error *err);

#endif
