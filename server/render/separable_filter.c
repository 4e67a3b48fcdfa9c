/* separable_filter.c — x/y passes of a depth filter shader, drawn or dispatched. */
#include "separable_filter.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniforms of depth_filter_common.glsl, looked up by name: a filter that
 * does not use one (the binomial one has a single kernel size) lets the
 * linker drop it, and setting a dropped location would be an error. */
enum { AXIS, PIXEL_SCALE, PARTICLE_RADIUS, DEPTH_JUMP, FIXED_RADIUS, RADII_PER_KERNEL, SOURCE_SIZE, STORE_BACKGROUND };
static const char *const UNIFORM_NAMES[FC_FILTER_UNIFORMS] = {"axis",         "pixel_scale",      "particle_radius",
                                                              "depth_jump",   "fixed_radius",     "radii_per_kernel",
                                                              "source_size",  "store_background"};
/* MAX_KERNEL_RADIUS of depth_filter_common.glsl. */
#define MAX_KERNEL_RADIUS 64u

static fc_code build_program(const char *shader_dir, const char *shader_file, fc_separable_filter *f,
                             fc_error *err)
{
    if (fc_shader_stage(shader_file) != GL_COMPUTE_SHADER) {
        glCreateVertexArrays(1, &f->empty_vertex_array);
        const char *files[] = {"fullscreen.vert.glsl", "depth_filter_common.glsl", shader_file};
        return fc_program_build(shader_dir, files, 3, &f->program, err);
    }
    const char *files[] = {"depth_filter_common.glsl", shader_file};
    fc_code code = fc_program_build(shader_dir, files, 2, &f->program, err);
    if (code != FC_OK)
        return code;
    GLint group[3] = {0, 0, 0};
    glGetProgramiv(f->program, GL_COMPUTE_WORK_GROUP_SIZE, group);
    f->group_size[0] = group[0];
    f->group_size[1] = group[1];
    return fc_gl_check("querying a filter's workgroup size", err);
}

fc_code fc_separable_filter_create(const char *shader_dir, const char *shader_file, GLenum color_format,
                                   float radii_per_kernel, fc_separable_filter *f, fc_error *err)
{
    *f = (fc_separable_filter){.radii_per_kernel = radii_per_kernel};
    for (int i = 0; i < 2; i++)
        f->ping_pong[i] = fc_render_target_init(color_format, false, false);
    fc_code code = build_program(shader_dir, shader_file, f, err);
    for (int i = 0; code == FC_OK && i < FC_FILTER_UNIFORMS; i++)
        f->uniform[i] = glGetUniformLocation(f->program, UNIFORM_NAMES[i]);   /* -1 when dropped: ignored */
    return code;
}

void fc_separable_filter_destroy(fc_separable_filter *f)
{
    glDeleteProgram(f->program);
    glDeleteVertexArrays(1, &f->empty_vertex_array);
    for (int i = 0; i < 2; i++)
        fc_render_target_release(&f->ping_pong[i]);
    f->program = f->empty_vertex_array = 0;
}

fc_code fc_separable_filter_begin(fc_separable_filter *f, const fc_render_target *depth,
                                  const fc_smoothing_params *grid, fc_error *err)
{
    for (int i = 0; i < 2; i++) {
        fc_code code = fc_render_target_resize(&f->ping_pong[i], depth->width, depth->height, err);
        if (code != FC_OK)
            return code;
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(f->program);
    glUniform2f(f->uniform[PIXEL_SCALE], grid->pixel_scale[0], grid->pixel_scale[1]);
    glUniform1f(f->uniform[PARTICLE_RADIUS], grid->particle_radius);
    glUniform1f(f->uniform[DEPTH_JUMP], grid->depth_jump);
    uint32_t radius = grid->filter_radius < MAX_KERNEL_RADIUS ? grid->filter_radius : MAX_KERNEL_RADIUS;
    glUniform1i(f->uniform[FIXED_RADIUS], (GLint)radius);
    glUniform1f(f->uniform[RADII_PER_KERNEL], f->radii_per_kernel);
    f->passes_since_begin = 0;
    return FC_OK;
}

/* Each invocation filters a run of FC_FILTER_RUN pixels along the axis. */
static void dispatch_pass(const fc_separable_filter *f, const fc_render_target *destination, int axis)
{
    glBindImageTexture(0, destination->color, 0, GL_FALSE, 0, GL_WRITE_ONLY, destination->color_format);
    uint32_t run[2] = {axis == 0 ? FC_FILTER_RUN : 1, axis == 1 ? FC_FILTER_RUN : 1};
    fc_gl_dispatch_over_image(destination->width, destination->height, (uint32_t)f->group_size[0] * run[0],
                              (uint32_t)f->group_size[1] * run[1]);
}

const fc_render_target *fc_separable_filter_pass(fc_separable_filter *f, const fc_render_target *source, int axis)
{
    const fc_render_target *destination = source == &f->ping_pong[0] ? &f->ping_pong[1] : &f->ping_pong[0];
    glUniform2i(f->uniform[AXIS], axis == 0, axis == 1);
    glUniform2i(f->uniform[SOURCE_SIZE], (GLint)source->width, (GLint)source->height);
    /* The first pass writes ping_pong[0], the second ping_pong[1]: every pixel. */
    glUniform1i(f->uniform[STORE_BACKGROUND], f->passes_since_begin < 2);
    f->passes_since_begin++;
    glBindTextureUnit(0, source->color);
    if (f->group_size[0] > 0) {
        dispatch_pass(f, destination, axis);
    } else {
        fc_render_target_bind(destination);
        fc_gl_draw_fullscreen(f->empty_vertex_array);
    }
    return destination;
}

fc_code fc_separable_filter_run(fc_separable_filter *f, const fc_render_target *depth,
                                const fc_smoothing_params *grid, const fc_render_target **result, fc_error *err)
{
    *result = depth;
    if (grid->iterations == 0)
        return FC_OK;
    fc_code code = fc_separable_filter_begin(f, depth, grid, err);
    if (code != FC_OK)
        return code;
    const fc_render_target *source = depth;
    for (uint32_t i = 0; i < grid->iterations; i++) {
        source = fc_separable_filter_pass(f, source, 0);
        source = fc_separable_filter_pass(f, source, 1);
    }
    *result = source;
    return fc_gl_check("separable depth filter", err);
}
