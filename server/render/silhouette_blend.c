/* silhouette_blend.c — colour blend over silhouettes after reduced-resolution smoothing. */
#include "silhouette_blend.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations and texture units fixed by the shaders. */
enum { LOC_BLOCK = 0, LOC_DEPTH_JUMP = 1, LOC_SHADED_SIZE = 40, LOC_LOW_SIZE = 41 };
enum { UNIT_SHADED = 0, UNIT_LOW_DEPTH = 1 };

fc_code fc_silhouette_blend_create(const char *shader_dir, fc_silhouette_blend *sb, fc_error *err)
{
    *sb = (fc_silhouette_blend){
        .srgb_target = fc_render_target_init(GL_SRGB8_ALPHA8, false, false),
        .float_target = fc_render_target_init(GL_RGBA32F, false, false),
    };
    glCreateVertexArrays(1, &sb->empty_vertex_array);
    const char *files[] = {"fullscreen.vert.glsl", "depth_footprint.frag.glsl", "silhouette_blend.frag.glsl"};
    return fc_program_build(shader_dir, files, sizeof files / sizeof files[0], &sb->program, err);
}

void fc_silhouette_blend_destroy(fc_silhouette_blend *sb)
{
    glDeleteProgram(sb->program);
    glDeleteVertexArrays(1, &sb->empty_vertex_array);
    fc_render_target_release(&sb->srgb_target);
    fc_render_target_release(&sb->float_target);
    sb->program = sb->empty_vertex_array = 0;
}

fc_code fc_silhouette_blend_run(fc_silhouette_blend *sb, const fc_render_target *shaded,
                                const fc_render_target *low_depth, uint32_t block, float depth_jump, bool want_u8,
                                const fc_render_target **result, fc_error *err)
{
    fc_render_target *target = want_u8 ? &sb->srgb_target : &sb->float_target;
    fc_code code = fc_render_target_resize(target, shaded->width, shaded->height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(target);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    /* Blending happens in linear RGB: sRGB texels decode on fetch and encode on write. */
    if (want_u8)
        glEnable(GL_FRAMEBUFFER_SRGB);
    else
        glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(sb->program);
    glUniform1i(LOC_BLOCK, (GLint)block);
    glUniform1f(LOC_DEPTH_JUMP, depth_jump);
    glUniform2i(LOC_SHADED_SIZE, (GLint)shaded->width, (GLint)shaded->height);
    glUniform2i(LOC_LOW_SIZE, (GLint)low_depth->width, (GLint)low_depth->height);
    glBindTextureUnit(UNIT_SHADED, shaded->color);
    glBindTextureUnit(UNIT_LOW_DEPTH, low_depth->color);
    fc_gl_draw_fullscreen(sb->empty_vertex_array);
    glDisable(GL_FRAMEBUFFER_SRGB);
    *result = target;
    return fc_gl_check("silhouette colour blend", err);
}
