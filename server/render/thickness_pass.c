/* thickness_pass.c — additive per-particle thickness, resampled and blurred. */
#include "thickness_pass.h"

#include <math.h>

#include "fc_colormap.h"
#include "gl_util.h"

/* Uniform locations fixed by layout(location) in thickness_chord.glsl and thickness_color.frag.glsl. */
enum { LOC_FLOOR_PLANE = 10, LOC_COLOR_RANGE = 11, LOC_COLORMAP = 16 };
/* The blur runs at this fraction of the image's resolution (or the splat's,
 * where lower): thickness is a low-frequency quantity (Janisz 2012, §4.1.3). */
#define BLUR_SCALE 0.5f

fc_code fc_thickness_pass_create(const char *shader_dir, fc_thickness_pass *pass, fc_error *err)
{
    pass->color_splat = fc_render_target_init(GL_RGBA32F, false, true);
    fc_code code = fc_thickness_filter_create(shader_dir, &pass->filter, err);
    if (code == FC_OK)
        code = fc_sphere_sprites_create_shaped(shader_dir, "thickness_chord.glsl", "thickness_color.frag.glsl",
                                               &pass->color_sprites, err);
    if (code == FC_OK)
        code = fc_thickness_filter_create_color(shader_dir, &pass->color_filter, err);
    return code;
}

void fc_thickness_pass_destroy(fc_thickness_pass *pass)
{
    fc_thickness_filter_destroy(&pass->color_filter);
    fc_sphere_sprites_destroy(&pass->color_sprites);
    fc_render_target_release(&pass->color_splat);
    fc_thickness_filter_destroy(&pass->filter);
}

static uint32_t scaled(uint32_t size, float scale)
{
    uint32_t n = (uint32_t)lroundf((float)size * scale);
    return n > 0 ? n : 1;
}

fc_view fc_thickness_view(const fc_view *view, float scale)
{
    fc_view reduced = *view;
    reduced.width = scaled(view->width, scale);
    reduced.height = scaled(view->height, scale);
    return reduced;
}

/* The colour's uniforms on the program that draws `particles`, and its values bound. */
static void apply_color(const fc_sphere_sprites *sprites, const fc_particle_buffer *particles,
                        const fc_thickness_color *color)
{
    GLuint program = fc_sphere_sprites_program(sprites, particles);
    glProgramUniform2f(program, LOC_COLOR_RANGE, color->range[0], color->range[1]);
    glProgramUniform3fv(program, LOC_COLORMAP, FC_COLORMAP_ENTRIES, &color->colormap[0][0]);
    fc_color_values_bind(color->values);
}

/* Every particle adds its chord times its colour into pass->color_splat. */
static fc_code splat_color(fc_thickness_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                           const fc_thickness_params *params, fc_error *err)
{
    fc_render_target *target = &pass->color_splat;
    fc_code code = fc_render_target_resize(target, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    const fc_sphere_sprites *sprites = &pass->color_sprites;
    fc_render_target_bind(target);
    const GLfloat empty[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(target->framebuffer, GL_COLOR, 0, empty);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glProgramUniform4fv(fc_sphere_sprites_program(sprites, particles), LOC_FLOOR_PLANE, 1, params->floor_plane);
    apply_color(sprites, particles, params->color);
    fc_sphere_sprites_draw(sprites, particles, view, params->radius);
    glDisable(GL_BLEND);
    return fc_gl_check("thickness pass", err);
}

/* Variance, in squared image pixels, that the resampling alone blurs the
 * thickness by: averaging k x k splat texels into a blur texel (a box of k
 * samples) and the composite's bilinear lookup of the blur texels (a tent
 * one blur texel wide each side). */
static float resampling_variance(float splat_scale, float blur_scale)
{
    float splat_texel = 1.0f / splat_scale, blur_texel = 1.0f / blur_scale;
    float k = splat_scale / blur_scale;
    return (k * k - 1.0f) / 12.0f * splat_texel * splat_texel + blur_texel * blur_texel / 6.0f;
}

/* The Gaussian's standard deviation in blur texels: what the blur radius
 * asks for, less what the resampling already blurs. */
static float residual_sigma(uint32_t blur, float splat_scale, float blur_scale)
{
    /* The blur radius is where the filter cuts the Gaussian off, three
     * standard deviations out. */
    float sigma = (float)blur / 3.0f;
    float variance = sigma * sigma - resampling_variance(splat_scale, blur_scale);
    return variance > 0.0f ? sqrtf(variance) * blur_scale : 0.0f;
}

static fc_code blur(fc_thickness_pass *pass, const fc_render_target *splatted, const fc_view *view,
                    const fc_thickness_params *params, const fc_render_target **result, fc_error *err)
{
    fc_thickness_filter *filter = params->color ? &pass->color_filter : &pass->filter;
    *result = splatted;
    fc_code code = FC_OK;
    if (params->blur > 0) {
        float blur_scale = fminf(params->scale, BLUR_SCALE);
        float sigma = residual_sigma(params->blur, params->scale, blur_scale);
        code = fc_thickness_filter_run(filter, splatted, sigma, scaled(view->width, blur_scale),
                                       scaled(view->height, blur_scale), result, err);
    }
    bool reduced = (*result)->width != view->width || (*result)->height != view->height;
    if (code == FC_OK && params->at_view_size && reduced)
        code = fc_thickness_filter_upsample(filter, *result, view->width, view->height, result, err);
    return code;
}

fc_code fc_thickness_pass_run(fc_thickness_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                              const fc_thickness_params *params, const fc_render_target **result, fc_error *err)
{
    float scale = params->scale;
    fc_view reduced = fc_thickness_view(view, scale);
    fc_pass_profile *profile = params->profile;
    /* The depth pass splats the thickness alone (at scale 1 it has, with the depth), never its colour. */
    const fc_render_target *splatted = params->color ? &pass->color_splat : &params->depth->thickness;
    fc_code code = FC_OK;
    if (params->color || (scale != 1.0f && !params->splatted)) {
        const char *name = params->splat_name ? params->splat_name : "thickness splat";
        fc_pass_profile_begin(profile, params->color ? "thickness + colour splat" : name);
        code = params->color ? splat_color(pass, particles, &reduced, params, err)
                             : fc_depth_pass_run_thickness(params->depth, particles, &reduced, params->radius,
                                                           params->floor_plane, err);
        fc_pass_profile_end(profile);
    }
    *result = splatted;
    if (code != FC_OK)
        return code;
    fc_pass_profile_begin(profile, "thickness blur");
    code = blur(pass, splatted, view, params, result, err);
    fc_pass_profile_end(profile);
    return code;
}

static void tally_filter(const fc_thickness_filter *filter, fc_gpu_memory *m)
{
    fc_render_target_tally(&filter->across, m);
    fc_render_target_tally(&filter->result, m);
    fc_render_target_tally(&filter->upsampled, m);
}

static void trim_filter(fc_thickness_filter *filter)
{
    fc_render_target_release(&filter->across);
    fc_render_target_release(&filter->result);
    fc_render_target_release(&filter->upsampled);
}

void fc_thickness_pass_tally(const fc_thickness_pass *pass, fc_gpu_memory *m)
{
    tally_filter(&pass->filter, m);
    fc_render_target_tally(&pass->color_splat, m);
    tally_filter(&pass->color_filter, m);
}

void fc_thickness_pass_trim(fc_thickness_pass *pass)
{
    trim_filter(&pass->filter);
    fc_render_target_release(&pass->color_splat);
    trim_filter(&pass->color_filter);
}
