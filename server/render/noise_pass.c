/* noise_pass.c — additive splatting of per-particle surface noise. */
#include "noise_pass.h"

#include "gl_util.h"

/* Locations and units fixed by layout() in noise.frag.glsl. */
enum { LOC_NOISE_AMPLITUDE = 10 };
enum { UNIT_SURFACE_DEPTH = 0 };

fc_code fc_noise_pass_create(const char *shader_dir, fc_noise_pass *pass, fc_error *err)
{
    pass->target = fc_render_target_init(GL_R32F, false, false);
    return fc_sphere_sprites_create_with(shader_dir, "particle_attributes.frag.glsl", "noise.frag.glsl",
                                         &pass->sprites, err);
}

void fc_noise_pass_destroy(fc_noise_pass *pass)
{
    fc_sphere_sprites_destroy(&pass->sprites);
    fc_render_target_release(&pass->target);
}

fc_code fc_noise_pass_run(fc_noise_pass *pass, const fc_particle_buffer *surface,
                          const fc_particle_attributes *attributes, const fc_render_target *surface_depth,
                          const fc_view *view, float radius, float amplitude, fc_error *err)
{
    fc_code code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    const GLfloat none = 0.0f;
    glClearNamedFramebufferfv(pass->target.framebuffer, GL_COLOR, 0, &none);
    if (!(amplitude > 0.0f) || surface->count == 0)
        return fc_gl_check("noise pass", err);
    fc_render_target_bind(&pass->target);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    /* Splats of either sign sum into N. */
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glProgramUniform1f(pass->sprites.program, LOC_NOISE_AMPLITUDE, amplitude);
    glBindTextureUnit(UNIT_SURFACE_DEPTH, surface_depth->color);
    fc_particle_attributes_bind(attributes);
    fc_sphere_sprites_draw(&pass->sprites, surface, view, radius);
    glDisable(GL_BLEND);
    return fc_gl_check("noise pass", err);
}
