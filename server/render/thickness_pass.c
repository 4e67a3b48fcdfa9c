/* thickness_pass.c — additive per-particle thickness. */
#include "thickness_pass.h"

#include "gl_util.h"

fc_code fc_thickness_pass_create(const char *shader_dir, fc_thickness_pass *pass, fc_error *err)
{
    pass->target = fc_render_target_init(GL_R32F, false, false);
    return fc_sphere_sprites_create(shader_dir, "thickness.frag.glsl", &pass->sprites, err);
}

void fc_thickness_pass_destroy(fc_thickness_pass *pass)
{
    fc_sphere_sprites_destroy(&pass->sprites);
    fc_render_target_release(&pass->target);
}

fc_code fc_thickness_pass_run(fc_thickness_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                              float radius, fc_error *err)
{
    fc_code code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(&pass->target);
    const GLfloat empty = 0.0f;
    glClearNamedFramebufferfv(pass->target.framebuffer, GL_COLOR, 0, &empty);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    fc_sphere_sprites_draw(&pass->sprites, particles, view, radius);
    glDisable(GL_BLEND);
    return fc_gl_check("thickness pass", err);
}
