/* curvature_flow.c — ping-pong iterations of curvature_flow.frag.glsl. */
#include "curvature_flow.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in curvature_flow.frag.glsl. */
enum { LOC_PIXEL_SCALE = 0, LOC_DEPTH_JUMP = 1 };

fc_code fc_curvature_flow_create(const char *shader_dir, fc_curvature_flow *cf, fc_error *err)
{
    *cf = (fc_curvature_flow){0};
    for (int i = 0; i < 2; i++)
        cf->ping_pong[i] = fc_render_target_init(GL_R32F, false, false);
    glCreateVertexArrays(1, &cf->empty_vertex_array);
    const char *files[] = {"fullscreen.vert.glsl", "curvature_flow.frag.glsl"};
    return fc_program_build(shader_dir, files, 2, &cf->program, err);
}

void fc_curvature_flow_destroy(fc_curvature_flow *cf)
{
    glDeleteProgram(cf->program);
    glDeleteVertexArrays(1, &cf->empty_vertex_array);
    for (int i = 0; i < 2; i++)
        fc_render_target_release(&cf->ping_pong[i]);
    cf->program = cf->empty_vertex_array = 0;
}

fc_code fc_curvature_flow_run(fc_curvature_flow *cf, const fc_render_target *depth, uint32_t iterations,
                              const float pixel_scale[2], float depth_jump, const fc_render_target **result,
                              fc_error *err)
{
    *result = depth;
    if (iterations == 0)
        return FC_OK;
    for (int i = 0; i < 2; i++) {
        fc_code code = fc_render_target_resize(&cf->ping_pong[i], depth->width, depth->height, err);
        if (code != FC_OK)
            return code;
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(cf->program);
    glUniform2f(LOC_PIXEL_SCALE, pixel_scale[0], pixel_scale[1]);
    glUniform1f(LOC_DEPTH_JUMP, depth_jump);
    const fc_render_target *source = depth;
    for (uint32_t i = 0; i < iterations; i++) {
        const fc_render_target *destination = &cf->ping_pong[i % 2];
        fc_render_target_bind(destination);
        glBindTextureUnit(0, source->color);
        fc_gl_draw_fullscreen(cf->empty_vertex_array);
        source = destination;
    }
    *result = source;
    return fc_gl_check("curvature flow", err);
}
