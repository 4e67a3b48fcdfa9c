/* separable_filter.c — x/y passes of a depth filter shader, drawn or dispatched. */
#include "separable_filter.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniforms of depth_filter_common.glsl, looked up by name: a filter that
 * does not use one (the binomial one has a single kernel size) lets the
 * linker drop it, and setting a dropped location would be an error. */
enum { AXIS, PIXEL_SCALE, PARTICLE_RADIUS, DEPTH_JUMP, FIXED_RADIUS, RADII_PER_KERNEL, SOURCE_SIZE };
static const char *const UNIFORM_NAMES[FC_FILTER_UNIFORMS] = {"axis",       "pixel_scale",  "particle_radius",
                                                              "depth_jump", "fixed_radius", "radii_per_kernel",
                                                              "source_size"};
/* A compute filter's FluidBlocks buffer binding. */
#define BIND_FLUID_BLOCKS 0u
/* MAX_KERNEL_RADIUS of depth_filter_common.glsl. */
#define MAX_KERNEL_RADIUS 64u

/* The preprocessor lines of each program of a compute filter. */
static const char *const PROGRAM_DEFINES[FC_FILTER_PROGRAMS] = {NULL, "#define FC_FIXED_KERNEL 1\n"};

static fc_code build_programs(const char *shader_dir, const char *shader_file, fc_separable_filter *f,
                              fc_error *err)
{
    if (fc_shader_stage(shader_file) != GL_COMPUTE_SHADER) {
        glCreateVertexArrays(1, &f->empty_vertex_array);
        const char *files[] = {"fullscreen.vert.glsl", "depth_filter_common.glsl", shader_file};
        return fc_program_build(shader_dir, files, 3, &f->programs[0], err);
    }
    fc_code code = fc_fluid_blocks_create(shader_dir, &f->blocks, err);
    if (code != FC_OK)
        return code;
    const char *files[] = {"depth_filter_common.glsl", shader_file};
    for (int i = 0; i < FC_FILTER_PROGRAMS; i++) {
        code = fc_program_build_defines(shader_dir, PROGRAM_DEFINES[i], files, 2, &f->programs[i], err);
        if (code != FC_OK)
            return code;
    }
    f->compute = true;
    return FC_OK;
}

fc_code fc_separable_filter_create(const char *shader_dir, const char *shader_file, GLenum color_format,
                                   float radii_per_kernel, fc_separable_filter *f, fc_error *err)
{
    *f = (fc_separable_filter){.radii_per_kernel = radii_per_kernel};
    for (int i = 0; i < 2; i++)
        f->ping_pong[i] = fc_render_target_init(color_format, false, false);
    fc_code code = build_programs(shader_dir, shader_file, f, err);
    for (int p = 0; code == FC_OK && p < FC_FILTER_PROGRAMS; p++)
        for (int i = 0; i < FC_FILTER_UNIFORMS; i++)   /* -1 when dropped or no such program: ignored */
            f->uniforms[p][i] = f->programs[p] ? glGetUniformLocation(f->programs[p], UNIFORM_NAMES[i]) : -1;
    f->program = f->programs[0];
    f->uniform = f->uniforms[0];
    return code;
}

void fc_separable_filter_destroy(fc_separable_filter *f)
{
    for (int p = 0; p < FC_FILTER_PROGRAMS; p++)
        glDeleteProgram(f->programs[p]);
    glDeleteVertexArrays(1, &f->empty_vertex_array);
    fc_fluid_blocks_destroy(&f->blocks);
    for (int i = 0; i < 2; i++)
        fc_render_target_release(&f->ping_pong[i]);
    f->programs[0] = f->programs[1] = f->program = f->empty_vertex_array = 0;
}

/* A compute filter stores fluid pixels only, on the blocks that hold fluid:
 * both targets start as background (0) and the blocks are listed. */
static fc_code prepare_compute(fc_separable_filter *f, const fc_render_target *depth, fc_error *err)
{
    for (int i = 0; i < 2; i++)
        glClearTexSubImage(f->ping_pong[i].color, 0, 0, 0, 0, (GLsizei)depth->width, (GLsizei)depth->height, 1,
                           GL_RED, GL_FLOAT, NULL);
    return fc_fluid_blocks_find(&f->blocks, depth, err);
}

fc_code fc_separable_filter_begin(fc_separable_filter *f, const fc_render_target *depth,
                                  const fc_smoothing_params *grid, fc_error *err)
{
    for (int i = 0; i < 2; i++) {
        fc_code code = fc_render_target_resize(&f->ping_pong[i], depth->width, depth->height, err);
        if (code != FC_OK)
            return code;
    }
    if (f->compute) {
        fc_code code = prepare_compute(f, depth, err);
        if (code != FC_OK)
            return code;
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    int variant = grid->filter_radius > 0 && f->programs[FC_FILTER_KERNEL_FIXED] ? FC_FILTER_KERNEL_FIXED
                                                                               : FC_FILTER_KERNEL_FROM_DEPTH;
    f->program = f->programs[variant];
    f->uniform = f->uniforms[variant];
    glUseProgram(f->program);
    glBindTextureUnit(1, depth->color);
    glUniform2f(f->uniform[PIXEL_SCALE], grid->pixel_scale[0], grid->pixel_scale[1]);
    glUniform1f(f->uniform[PARTICLE_RADIUS], grid->particle_radius);
    glUniform1f(f->uniform[DEPTH_JUMP], grid->depth_jump);
    uint32_t radius = grid->filter_radius < MAX_KERNEL_RADIUS ? grid->filter_radius : MAX_KERNEL_RADIUS;
    glUniform1i(f->uniform[FIXED_RADIUS], (GLint)radius);
    glUniform1f(f->uniform[RADII_PER_KERNEL], f->radii_per_kernel);
    return FC_OK;
}

/* One workgroup per block that holds fluid, writing `destination` as image unit 0. */
static void dispatch_pass(const fc_separable_filter *f, const fc_render_target *destination)
{
    glBindImageTexture(0, destination->color, 0, GL_FALSE, 0, GL_WRITE_ONLY, destination->color_format);
    fc_fluid_blocks_dispatch(&f->blocks, BIND_FLUID_BLOCKS);
}

const fc_render_target *fc_separable_filter_pass(fc_separable_filter *f, const fc_render_target *source, int axis)
{
    const fc_render_target *destination = source == &f->ping_pong[0] ? &f->ping_pong[1] : &f->ping_pong[0];
    glUniform2i(f->uniform[AXIS], axis == 0, axis == 1);
    glUniform2i(f->uniform[SOURCE_SIZE], (GLint)source->width, (GLint)source->height);
    glBindTextureUnit(0, source->color);
    if (f->compute) {
        dispatch_pass(f, destination);
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
