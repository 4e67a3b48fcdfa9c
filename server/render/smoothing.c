/* smoothing.c — dispatch of the depth smoothing methods, at full or reduced
 * resolution. */
#include "smoothing.h"

#include "fc_error.h"

/* Automatic kernel half-widths in projected particle radii. Two radii span a
 * particle and its neighbours' overlap, enough to merge the spheres into one
 * surface without rounding off features of a few particles. */
#define BILATERAL_RADII_PER_KERNEL 2.0f
#define NARROW_RANGE_RADII_PER_KERNEL 2.0f

fc_code fc_smoother_create(const char *shader_dir, fc_smoother *s, fc_error *err)
{
    *s = (fc_smoother){0};
    fc_code code = fc_curvature_flow_create(shader_dir, &s->curvature_flow, err);
    if (code == FC_OK)
        code = fc_separable_filter_create(shader_dir, "bilateral_filter.frag.glsl", GL_R32F,
                                          BILATERAL_RADII_PER_KERNEL, &s->bilateral, err);
    if (code == FC_OK)
        code = fc_separable_filter_create(shader_dir, "narrow_range_filter.comp.glsl", GL_R32F,
                                          NARROW_RANGE_RADII_PER_KERNEL, &s->narrow_range, err);
    if (code == FC_OK)
        code = fc_binomial_filter_create(shader_dir, &s->binomial, err);
    if (code == FC_OK)
        code = fc_resolution_scale_create(shader_dir, &s->resolution, err);
    if (code == FC_OK)
        code = fc_silhouette_blend_create(shader_dir, &s->silhouette_blend, err);
    return code;
}

void fc_smoother_destroy(fc_smoother *s)
{
    fc_silhouette_blend_destroy(&s->silhouette_blend);
    fc_resolution_scale_destroy(&s->resolution);
    fc_binomial_filter_destroy(&s->binomial);
    fc_separable_filter_destroy(&s->narrow_range);
    fc_separable_filter_destroy(&s->bilateral);
    fc_curvature_flow_destroy(&s->curvature_flow);
}

/* Runs the method on `depth`, whose grid `grid` describes. */
static fc_code run_method_passes(fc_smoother *s, const fc_render_target *depth, const fc_smoothing_params *grid,
                          const fc_render_target **result, fc_error *err)
{
    switch (grid->method) {
    case FC_SMOOTHING_NONE:
        *result = depth;
        return FC_OK;
    case FC_SMOOTHING_CURVATURE:
        return fc_curvature_flow_run(&s->curvature_flow, depth, grid->iterations, grid->pixel_scale,
                                     grid->depth_jump, result, err);
    case FC_SMOOTHING_BILATERAL:
        return fc_separable_filter_run(&s->bilateral, depth, grid, result, err);
    case FC_SMOOTHING_BINOMIAL:
        return fc_binomial_filter_run(&s->binomial, depth, grid, result, err);
    case FC_SMOOTHING_NARROW:
        return fc_separable_filter_run(&s->narrow_range, depth, grid, result, err);
    }
    return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown smoothing method %d", (int)grid->method);
}

static fc_code run_method(fc_smoother *s, const fc_render_target *depth, const fc_smoothing_params *grid,
                          const fc_render_target **result, fc_error *err)
{
    fc_pass_profile_begin(grid->profile, "smoothing filter");
    fc_code code = run_method_passes(s, depth, grid, result, err);
    fc_pass_profile_end(grid->profile);
    return code;
}

/* The parameters for a grid with `block` image pixels per texel: one texel
 * spans `block` times the view a pixel does, and a kernel as many fewer texels
 * (never less than one, so a fixed kernel stays fixed). */
static fc_smoothing_params coarser_grid(const fc_smoothing_params *image, uint32_t block)
{
    fc_smoothing_params grid = *image;
    for (int i = 0; i < 2; i++)
        grid.pixel_scale[i] = image->pixel_scale[i] * (float)block;
    if (image->filter_radius > 0) {
        uint32_t rounded = (image->filter_radius + block / 2) / block;
        grid.filter_radius = rounded > 0 ? rounded : 1;
    }
    return grid;
}

fc_code fc_smoother_run(fc_smoother *s, const fc_render_target *depth, const fc_smoothing_params *params,
                        const fc_render_target **result, fc_error *err)
{
    s->low_resolution = NULL;
    uint32_t block = fc_resolution_scale_block(params->smooth_scale);
    bool smooths = params->method != FC_SMOOTHING_NONE && params->iterations > 0;
    if (block == 1 || !smooths)
        return run_method(s, depth, params, result, err);

    fc_smoothing_params grid = coarser_grid(params, block);
    const fc_render_target *low = NULL, *smoothed = NULL;
    fc_pass_profile_begin(params->profile, "smoothing downsample");
    fc_code code = fc_resolution_scale_down(&s->resolution, depth, block, &low, err);
    fc_pass_profile_end(params->profile);
    if (code == FC_OK)
        code = run_method(s, low, &grid, &smoothed, err);
    fc_pass_profile_begin(params->profile, "smoothing upsample");
    if (code == FC_OK)
        code = fc_resolution_scale_up(&s->resolution, smoothed, depth, block, params->depth_jump, result, err);
    fc_pass_profile_end(params->profile);
    if (code == FC_OK) {
        s->low_resolution = smoothed;
        s->block = block;
        s->depth_jump = params->depth_jump;
    }
    return code;
}

fc_code fc_smoother_blend_silhouettes(fc_smoother *s, const fc_render_target *shaded, bool want_u8,
                                      const fc_render_target **result, fc_error *err)
{
    *result = shaded;
    if (!s->low_resolution)
        return FC_OK;
    return fc_silhouette_blend_run(&s->silhouette_blend, shaded, s->low_resolution, s->block, s->depth_jump, want_u8,
                                   result, err);
}

void fc_smoother_tally(const fc_smoother *s, fc_gpu_memory *m)
{
    const fc_render_target *ping_pongs[] = {s->curvature_flow.ping_pong, s->bilateral.ping_pong,
                                            s->narrow_range.ping_pong, s->binomial.passes.ping_pong};
    for (size_t i = 0; i < sizeof ping_pongs / sizeof ping_pongs[0]; i++) {
        fc_render_target_tally(&ping_pongs[i][0], m);
        fc_render_target_tally(&ping_pongs[i][1], m);
    }
    fc_fluid_blocks_tally(&s->narrow_range.blocks, m);
    fc_render_target_tally(&s->resolution.low, m);
    fc_render_target_tally(&s->resolution.full, m);
    fc_render_target_tally(&s->silhouette_blend.srgb_target, m);
    fc_render_target_tally(&s->silhouette_blend.float_target, m);
}

void fc_smoother_trim(fc_smoother *s)
{
    fc_render_target *ping_pongs[] = {s->curvature_flow.ping_pong, s->bilateral.ping_pong, s->narrow_range.ping_pong,
                                      s->binomial.passes.ping_pong};
    for (size_t i = 0; i < sizeof ping_pongs / sizeof ping_pongs[0]; i++) {
        fc_render_target_release(&ping_pongs[i][0]);
        fc_render_target_release(&ping_pongs[i][1]);
    }
    fc_fluid_blocks_release(&s->narrow_range.blocks);
    fc_render_target_release(&s->resolution.low);
    fc_render_target_release(&s->resolution.full);
    fc_render_target_release(&s->silhouette_blend.srgb_target);
    fc_render_target_release(&s->silhouette_blend.float_target);
    s->low_resolution = NULL;
}
