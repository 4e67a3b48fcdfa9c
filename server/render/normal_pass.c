/* normal_pass.c — the shading normal as an image. */
#include "normal_pass.h"

#include "gl_util.h"
#include "shader_program.h"

/* Locations and units fixed by layout() in camera.frag.glsl and surface_normal.frag.glsl. */
enum { LOC_FOCAL = 0, LOC_VIEWPORT = 5, LOC_PARTICLE_RADIUS = 12, LOC_HAS_NOISE = 19, LOC_SURFACE_SIZE = 42 };
enum { UNIT_SURFACE_DEPTH = 0, UNIT_NOISE = 3 };

fc_code fc_normal_pass_create(const char *shader_dir, fc_normal_pass *pass, fc_error *err)
{
    *pass = (fc_normal_pass){.target = fc_render_target_init(GL_RGBA32F, false, false)};
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    const char *files[] = {"fullscreen.vert.glsl", "camera.frag.glsl", "surface_normal.frag.glsl",
                           "normal.frag.glsl"};
    return fc_program_build(shader_dir, files, sizeof files / sizeof files[0], &pass->program, err);
}

void fc_normal_pass_destroy(fc_normal_pass *pass)
{
    glDeleteProgram(pass->program);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    fc_render_target_release(&pass->target);
    pass->program = pass->empty_vertex_array = 0;
}

void fc_surface_normal_bind(const fc_render_target *surface_depth, const fc_render_target *noise, float radius,
                            uint64_t uniforms)
{
    if (fc_uniform_active(uniforms, LOC_PARTICLE_RADIUS))
        glUniform1f(LOC_PARTICLE_RADIUS, radius);
    if (fc_uniform_active(uniforms, LOC_HAS_NOISE))
        glUniform1i(LOC_HAS_NOISE, noise != NULL);
    if (fc_uniform_active(uniforms, LOC_SURFACE_SIZE))
        glUniform2i(LOC_SURFACE_SIZE, (GLint)surface_depth->width, (GLint)surface_depth->height);
    glBindTextureUnit(UNIT_SURFACE_DEPTH, surface_depth->color);
    if (noise)
        glBindTextureUnit(UNIT_NOISE, noise->color);
}

fc_code fc_normal_pass_run(fc_normal_pass *pass, const fc_render_target *surface_depth,
                           const fc_render_target *noise, const fc_view *view, float radius,
                           const fc_render_target **result, fc_error *err)
{
    fc_code code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(&pass->target);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(pass->program);
    glUniform2f(LOC_FOCAL, view->fx, view->fy);
    glUniform2f(LOC_VIEWPORT, (float)view->width, (float)view->height);
    fc_surface_normal_bind(surface_depth, noise, radius, FC_ALL_UNIFORMS);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    *result = &pass->target;
    return fc_gl_check("normal pass", err);
}
