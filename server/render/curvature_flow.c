/* curvature_flow.c — ping-pong iterations of curvature_flow.comp.glsl. */
#include "curvature_flow.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in curvature_flow.comp.glsl. */
enum { LOC_PIXEL_SCALE = 0, LOC_DEPTH_JUMP = 1, LOC_SOURCE_SIZE = 40 };
/* Pixels one invocation steps: BLOCK_W x BLOCK_H of curvature_flow.comp.glsl. */
#define BLOCK_W 4u
#define BLOCK_H 4u

fc_code fc_curvature_flow_create(const char *shader_dir, fc_curvature_flow *cf, fc_error *err)
{
    *cf = (fc_curvature_flow){0};
    for (int i = 0; i < 2; i++)
        cf->ping_pong[i] = fc_render_target_init(GL_R32F, false, false);
    const char *files[] = {"curvature_flow.comp.glsl"};
    fc_code code = fc_program_build(shader_dir, files, 1, &cf->program, err);
    if (code != FC_OK)
        return code;
    glGetProgramiv(cf->program, GL_COMPUTE_WORK_GROUP_SIZE, cf->group_size);
    return fc_gl_check("querying the curvature flow's workgroup size", err);
}

void fc_curvature_flow_destroy(fc_curvature_flow *cf)
{
    glDeleteProgram(cf->program);
    for (int i = 0; i < 2; i++)
        fc_render_target_release(&cf->ping_pong[i]);
    cf->program = 0;
}

/* One step from `source` into `destination`. */
static void dispatch_step(const fc_curvature_flow *cf, const fc_render_target *source,
                          const fc_render_target *destination)
{
    glBindTextureUnit(0, source->color);
    fc_render_target_uniform_size(cf->program, LOC_SOURCE_SIZE, source);
    glBindImageTexture(0, destination->color, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    fc_gl_dispatch_over_image(destination->width, destination->height, (uint32_t)cf->group_size[0] * BLOCK_W,
                              (uint32_t)cf->group_size[1] * BLOCK_H);
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
        dispatch_step(cf, source, destination);
        source = destination;
    }
    *result = source;
    return fc_gl_check("curvature flow", err);
}
