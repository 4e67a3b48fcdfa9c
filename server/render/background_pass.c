/* background_pass.c — the scene behind the fluid. */
#include "background_pass.h"

#include "gl_util.h"
#include "shader_program.h"

/* Locations and units fixed by layout() in background.frag.glsl. */
enum { LOC_USE_CLIENT_IMAGE = 30, LOC_IMAGE_SCALE = 31 };
enum { UNIT_CLIENT_IMAGE = 0 };

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

/* The part of the image's uv square the view shows: all of one axis, the
 * centre of the other, so the image covers the view without distortion. */
static void apply_client_image(const fc_scene_textures *scene, const fc_view *view)
{
    bool use = scene && scene->background;
    glUniform1i(LOC_USE_CLIENT_IMAGE, use);
    if (!use)
        return;
    float view_aspect = (float)view->width / (float)view->height;
    float ratio = view_aspect / scene->background_aspect;
    glUniform2f(LOC_IMAGE_SCALE, ratio < 1.0f ? ratio : 1.0f, ratio < 1.0f ? 1.0f : 1.0f / ratio);
    glBindTextureUnit(UNIT_CLIENT_IMAGE, scene->background);
}

fc_code fc_background_pass_run(fc_background_pass *pass, const fc_view *view, const fc_environment *env,
                               const fc_scene_textures *scene, fc_error *err)
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
    apply_client_image(scene, view);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    return fc_gl_check("background pass", err);
}
