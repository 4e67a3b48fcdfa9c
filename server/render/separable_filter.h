/* separable_filter.h — a depth filter applied as 1-D passes along x, then y,
 * ping-ponging between two targets: the shape shared by the bilateral,
 * narrow-range and binomial smoothing (their shaders link
 * depth_filter_common.glsl, whose uniforms are set here). A filter is a
 * fragment shader drawn over the target, or a compute shader writing the
 * target's texture as an image, one workgroup per 8x8 block that holds fluid
 * (fluid_blocks.h): such a filter leaves the background (depth 0) at 0. */
#ifndef FC_SEPARABLE_FILTER_H
#define FC_SEPARABLE_FILTER_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "fluid_blocks.h"
#include "render_target.h"
#include "smoothing_params.h"

#define FC_FILTER_UNIFORMS 7

/* A compute filter's programs: the kernel half-width from each pixel's depth
 * (or fixed, as a uniform), and a variant built with FC_FIXED_KERNEL for
 * requests that fix it, which may share per-pixel work between pixels. */
enum { FC_FILTER_KERNEL_FROM_DEPTH, FC_FILTER_KERNEL_FIXED, FC_FILTER_PROGRAMS };

typedef struct fc_separable_filter {
    GLuint programs[FC_FILTER_PROGRAMS];   /* a fragment filter has the first only */
    GLint uniforms[FC_FILTER_PROGRAMS][FC_FILTER_UNIFORMS];   /* the common uniforms' locations, -1 where unused */
    GLuint program;                  /* the one begin chose */
    const GLint *uniform;            /* its uniforms' locations */
    GLuint empty_vertex_array;
    bool compute;                    /* a compute shader, else a fragment shader */
    float radii_per_kernel;          /* automatic half-width, in projected particle radii */
    fc_render_target ping_pong[2];   /* of the format the shader writes, sized to the input */
    fc_fluid_blocks blocks;          /* compute: the blocks of the run's depth that hold fluid */
} fc_separable_filter;

/* Links depth_filter_common.glsl and `shader_file` into a filter writing
 * `color_format`: with fullscreen.vert.glsl for a *.frag.glsl; a *.comp.glsl
 * runs one workgroup per listed block (reading the FluidBlocks buffer at
 * shader storage binding 0) and writes image unit 0; it is linked twice, the
 * second time with FC_FIXED_KERNEL defined, the program begin uses for a
 * fixed kernel half-width. */
fc_code fc_separable_filter_create(const char *shader_dir, const char *shader_file, GLenum color_format,
                                   float radii_per_kernel, fc_separable_filter *f, fc_error *err);
void fc_separable_filter_destroy(fc_separable_filter *f);

/* Sizes the targets to `depth` (a compute filter's: cleared to 0 over the
 * image, and the blocks of `depth` that hold fluid listed), binds the program
 * (the FC_FIXED_KERNEL one when `grid` fixes the kernel half-width and the
 * filter has it), sets the common uniforms from `grid` (parameters in the
 * pixels of the grid being filtered) and binds `depth` to texture unit 1 for
 * the whole run (the unfiltered depth, for filters that read it in every
 * pass); the caller may then set its own uniforms and run passes. */
fc_code fc_separable_filter_begin(fc_separable_filter *f, const fc_render_target *depth,
                                  const fc_smoothing_params *grid, fc_error *err);

/* One 1-D pass along `axis` (0 = x, 1 = y) from `source` into the ping-pong
 * target that is not `source`; returns that target. A compute filter runs on
 * the blocks begin listed: `source` must hold fluid in those blocks only
 * (begin's depth, or an earlier pass's output). */
const fc_render_target *fc_separable_filter_pass(fc_separable_filter *f, const fc_render_target *source, int axis);

/* begin, then grid->iterations pairs of x and y passes; *result is the last
 * target written (`depth` itself for no iterations). */
fc_code fc_separable_filter_run(fc_separable_filter *f, const fc_render_target *depth,
                                const fc_smoothing_params *grid, const fc_render_target **result, fc_error *err);

#endif
