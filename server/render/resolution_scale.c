/* resolution_scale.c — depth_downsample.frag.glsl and depth_upsample.frag.glsl. */
#include "resolution_scale.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in the shaders. */
enum { LOC_BLOCK = 0, LOC_DEPTH_JUMP = 1 };
/* The size of the image in use of the source: of depth_downsample.frag.glsl's
 * full-resolution depth, of depth_footprint.frag.glsl's low-resolution one. */
enum { LOC_DOWNSAMPLE_SOURCE_SIZE = 40, LOC_UPSAMPLE_LOW_SIZE = 41 };
/* Texture unit of the unsmoothed depth in depth_upsample.frag.glsl (the source is on 0). */
enum { UNIT_FULL_DEPTH = 1 };

fc_code fc_resolution_scale_create(const char *shader_dir, fc_resolution_scale *rs, fc_error *err)
{
    *rs = (fc_resolution_scale){
        .low = fc_render_target_init(GL_R32F, false, false),
        .full = fc_render_target_init(GL_R32F, false, false),
    };
    glCreateVertexArrays(1, &rs->empty_vertex_array);
    const char *down[] = {"fullscreen.vert.glsl", "depth_downsample.frag.glsl"};
    const char *up[] = {"fullscreen.vert.glsl", "depth_footprint.frag.glsl", "depth_upsample.frag.glsl"};
    fc_code code = fc_program_build(shader_dir, down, sizeof down / sizeof down[0], &rs->downsample_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, up, sizeof up / sizeof up[0], &rs->upsample_program, err);
    return code;
}

void fc_resolution_scale_destroy(fc_resolution_scale *rs)
{
    glDeleteProgram(rs->downsample_program);
    glDeleteProgram(rs->upsample_program);
    glDeleteVertexArrays(1, &rs->empty_vertex_array);
    fc_render_target_release(&rs->low);
    fc_render_target_release(&rs->full);
    rs->downsample_program = rs->upsample_program = rs->empty_vertex_array = 0;
}

uint32_t fc_resolution_scale_block(float smooth_scale)
{
    if (smooth_scale > 0.0f && smooth_scale <= 0.25f)
        return 4;
    if (smooth_scale > 0.0f && smooth_scale <= 0.5f)
        return 2;
    return 1;
}

/* Draws `program` into `target` with `source` on texture unit 0. */
static void draw(const fc_resolution_scale *rs, GLuint program, GLint source_size_location,
                 const fc_render_target *target, const fc_render_target *source, uint32_t block)
{
    fc_render_target_bind(target);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(program);
    glUniform1i(LOC_BLOCK, (GLint)block);
    fc_render_target_uniform_size(program, source_size_location, source);
    glBindTextureUnit(0, source->color);
    fc_gl_draw_fullscreen(rs->empty_vertex_array);
}

fc_code fc_resolution_scale_down(fc_resolution_scale *rs, const fc_render_target *depth, uint32_t block,
                                 const fc_render_target **low, fc_error *err)
{
    uint32_t width = (depth->width + block - 1) / block, height = (depth->height + block - 1) / block;
    fc_code code = fc_render_target_resize(&rs->low, width, height, err);
    if (code != FC_OK)
        return code;
    draw(rs, rs->downsample_program, LOC_DOWNSAMPLE_SOURCE_SIZE, &rs->low, depth, block);
    *low = &rs->low;
    return fc_gl_check("depth downsampling", err);
}

fc_code fc_resolution_scale_up(fc_resolution_scale *rs, const fc_render_target *smoothed,
                               const fc_render_target *depth, uint32_t block, float depth_jump,
                               const fc_render_target **full, fc_error *err)
{
    fc_code code = fc_render_target_resize(&rs->full, depth->width, depth->height, err);
    if (code != FC_OK)
        return code;
    glProgramUniform1f(rs->upsample_program, LOC_DEPTH_JUMP, depth_jump);
    glBindTextureUnit(UNIT_FULL_DEPTH, depth->color);
    draw(rs, rs->upsample_program, LOC_UPSAMPLE_LOW_SIZE, &rs->full, smoothed, block);
    *full = &rs->full;
    return fc_gl_check("depth upsampling", err);
}
