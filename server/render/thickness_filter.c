/* thickness_filter.c — Gaussian blur and upsampling of the thickness. */
#include "thickness_filter.h"

#include <math.h>

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in thickness_blur.frag.glsl. */
enum {
    LOC_AXIS = 0,
    LOC_SIGMA = 1,
    LOC_TAPS = 2,
    LOC_TARGET_SIZE = 3,
    LOC_SOURCE_SIZE = 4,
    LOC_SOURCE_TEXTURE_SIZE = 5
};
/* The kernel is cut at this many standard deviations, where weights are about 1%. */
#define KERNEL_SIGMAS 3.0f
/* Bounds the loop of the shader whatever blur a client asks for. */
#define MAX_TAPS 64

fc_code fc_thickness_filter_create(const char *shader_dir, fc_thickness_filter *f, fc_error *err)
{
    *f = (fc_thickness_filter){
        .across = fc_render_target_init(GL_R32F, false, true),
        .result = fc_render_target_init(GL_R32F, false, true),
    };
    glCreateVertexArrays(1, &f->empty_vertex_array);
    const char *files[] = {"fullscreen.vert.glsl", "thickness_blur.frag.glsl"};
    return fc_program_build(shader_dir, files, sizeof files / sizeof files[0], &f->program, err);
}

void fc_thickness_filter_destroy(fc_thickness_filter *f)
{
    glDeleteProgram(f->program);
    glDeleteVertexArrays(1, &f->empty_vertex_array);
    fc_render_target_release(&f->across);
    fc_render_target_release(&f->result);
    f->program = f->empty_vertex_array = 0;
}

/* One axis of the blur from `source` into `target`; `axis` 0 is x, 1 is y. */
static fc_code blur_axis(fc_thickness_filter *f, const fc_render_target *source, fc_render_target *target,
                         int axis, float sigma, uint32_t width, uint32_t height, fc_error *err)
{
    fc_code code = fc_render_target_resize(target, width, height, err);
    if (code != FC_OK)
        return code;
    /* The small margin keeps a sigma of exactly n/3 texels from rounding up to n + 1 taps. */
    int taps = sigma > 0.0f ? (int)ceilf(KERNEL_SIGMAS * sigma - 1e-3f) : 0;
    fc_render_target_bind(target);
    glUseProgram(f->program);
    glUniform2f(LOC_AXIS, axis == 0 ? 1.0f : 0.0f, axis == 1 ? 1.0f : 0.0f);
    glUniform1f(LOC_SIGMA, sigma);
    glUniform1i(LOC_TAPS, taps < MAX_TAPS ? taps : MAX_TAPS);
    glUniform2f(LOC_TARGET_SIZE, (float)width, (float)height);
    glUniform2f(LOC_SOURCE_SIZE, (float)source->width, (float)source->height);
    glUniform2f(LOC_SOURCE_TEXTURE_SIZE, (float)source->texture_width, (float)source->texture_height);
    glBindTextureUnit(0, source->color);
    fc_gl_draw_fullscreen(f->empty_vertex_array);
    return fc_gl_check("thickness blur", err);
}

fc_code fc_thickness_filter_run(fc_thickness_filter *f, const fc_render_target *source, float sigma,
                                uint32_t width, uint32_t height, const fc_render_target **result, fc_error *err)
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    const fc_render_target *vertical_source = source;
    fc_code code = FC_OK;
    if (sigma > 0.0f) {
        code = blur_axis(f, source, &f->across, 0, sigma, source->width, source->height, err);
        vertical_source = &f->across;
    }
    if (code == FC_OK)
        code = blur_axis(f, vertical_source, &f->result, 1, sigma, width, height, err);
    *result = &f->result;
    return code;
}
