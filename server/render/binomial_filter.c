/* binomial_filter.c — the smoothing and silhouette-map phases of
 * binomial_filter.frag.glsl. */
#include "binomial_filter.h"

#include <math.h>

#include "gl_util.h"

/* Uniform location and phases fixed by binomial_filter.frag.glsl. */
enum { LOC_PHASE = 6 };
enum { SMOOTH_FROM_DEPTH = 0, SMOOTH = 1, SILHOUETTE_START = 2, SILHOUETTE = 3, SILHOUETTE_FINISH = 4 };
/* MAX_KERNEL_RADIUS of depth_filter_common.glsl. */
#define MAX_KERNEL_RADIUS 64.0f

fc_code fc_binomial_filter_create(const char *shader_dir, fc_binomial_filter *b, fc_error *err)
{
    /* The kernel size comes from fc_binomial_kernel_radius, never from the shader. */
    return fc_separable_filter_create(shader_dir, "binomial_filter.frag.glsl", GL_RGBA32F, 0.0f, &b->passes, err);
}

void fc_binomial_filter_destroy(fc_binomial_filter *b)
{
    fc_separable_filter_destroy(&b->passes);
}

uint32_t fc_binomial_kernel_radius(const fc_smoothing_params *grid)
{
    /* A sphere of radius r at depth z spans r / (z C) pixels (C: pixel size at unit depth). */
    float c = fmaxf(grid->pixel_scale[0], grid->pixel_scale[1]);
    float radius = grid->filter_radius > 0 ? (float)grid->filter_radius
                                           : ceilf(grid->particle_radius / (grid->reference_depth * c));
    return (uint32_t)fminf(fmaxf(radius, 1.0f), MAX_KERNEL_RADIUS);
}

static const fc_render_target *phase_pass(fc_binomial_filter *b, const fc_render_target *source, int phase, int axis)
{
    glUniform1i(LOC_PHASE, phase);
    return fc_separable_filter_pass(&b->passes, source, axis);
}

fc_code fc_binomial_filter_run(fc_binomial_filter *b, const fc_render_target *depth, const fc_smoothing_params *grid,
                               const fc_render_target **result, fc_error *err)
{
    *result = depth;
    if (grid->iterations == 0)
        return FC_OK;
    fc_smoothing_params one_kernel = *grid;
    one_kernel.filter_radius = fc_binomial_kernel_radius(grid);
    fc_code code = fc_separable_filter_begin(&b->passes, depth, &one_kernel, err);
    if (code != FC_OK)
        return code;
    const fc_render_target *source = depth;
    uint32_t passes = 2 * grid->iterations;
    for (uint32_t i = 0; i < passes; i++)
        source = phase_pass(b, source, i == 0 ? SMOOTH_FROM_DEPTH : SMOOTH, (int)(i % 2));
    for (uint32_t i = 0; i < passes; i++) {
        int phase = i == 0 ? SILHOUETTE_START : i + 1 == passes ? SILHOUETTE_FINISH : SILHOUETTE;
        source = phase_pass(b, source, phase, (int)(i % 2));
    }
    *result = source;
    return fc_gl_check("binomial filter", err);
}
