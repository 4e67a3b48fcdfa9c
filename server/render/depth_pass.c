/* depth_pass.c — nearest sphere depth per pixel. */
#include "depth_pass.h"

#include "gl_util.h"

fc_code fc_depth_pass_create(const char *shader_dir, fc_depth_pass *pass, fc_error *err)
{
    pass->target = fc_render_target_init(GL_R32F, true, false);
    return fc_sphere_sprites_create(shader_dir, "depth.frag.glsl", &pass->sprites, err);
}

void fc_depth_pass_destroy(fc_depth_pass *pass)
{
    fc_sphere_sprites_destroy(&pass->sprites);
    fc_render_target_release(&pass->target);
}

fc_code fc_depth_pass_run(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                          float radius, fc_error *err)
{
    fc_code code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(&pass->target);
    const GLfloat no_fluid = 0.0f, farthest = 1.0f;
    glClearNamedFramebufferfv(pass->target.framebuffer, GL_COLOR, 0, &no_fluid);
    glClearNamedFramebufferfv(pass->target.framebuffer, GL_DEPTH, 0, &farthest);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    fc_sphere_sprites_draw(&pass->sprites, particles, view, radius);
    glDisable(GL_DEPTH_TEST);
    return fc_gl_check("depth pass", err);
}
