/* background_pass.c — sky and floor behind the fluid. */
#include "background_pass.h"

#include "gl_util.h"
#include "shader_program.h"

fc_code fc_background_pass_create(const char *shader_dir, fc_background_pass *pass, fc_error *err)
{
    *pass = (fc_background_pass){.target = fc_render_target_init(GL_RGBA16F, false, true)};
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    const char *files[] = {"fullscreen.vert.glsl", "camera.frag.glsl", "environment.frag.glsl",
                           "background.frag.glsl"};
    return fc_program_build(shader_dir, files, sizeof files / sizeof files[0], &pass->program, err);
}

void fc_background_pass_destroy(fc_background_pass *pass)
{
    glDeleteProgram(pass->program);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    fc_render_target_release(&pass->target);
    pass->program = pass->empty_vertex_array = 0;
}

fc_code fc_background_pass_run(fc_background_pass *pass, const fc_view *view, const fc_environment *env,
                               fc_error *err)
{
    fc_code code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(&pass->target);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(pass->program);
    fc_environment_apply(env, view);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    return fc_gl_check("background pass", err);
}
