/* fluid_blocks.c — see fluid_blocks.h. */
#include "fluid_blocks.h"

#include "gl_util.h"
#include "shader_program.h"

/* fluid_blocks.comp.glsl's bindings and locations. */
enum { BIND_DEPTH = 0, BIND_BLOCKS = 0, LOC_SOURCE_SIZE = 40 };
/* Its workgroup: 8 x 8 invocations, one block each. */
#define GROUP_SIDE 8u
/* The buffer's header: glDispatchComputeIndirect's three workgroup counts. */
#define HEADER_UINTS 3u

fc_code fc_fluid_blocks_create(const char *shader_dir, fc_fluid_blocks *b, fc_error *err)
{
    *b = (fc_fluid_blocks){0};
    const char *files[] = {"fluid_blocks.comp.glsl"};
    return fc_program_build(shader_dir, files, 1, &b->program, err);
}

void fc_fluid_blocks_release(fc_fluid_blocks *b)
{
    glDeleteBuffers(1, &b->buffer);
    b->buffer = 0;
    b->capacity = 0;
    b->bytes = 0;
}

void fc_fluid_blocks_destroy(fc_fluid_blocks *b)
{
    fc_fluid_blocks_release(b);
    glDeleteProgram(b->program);
    b->program = 0;
}

static uint32_t blocks_along(uint32_t pixels)
{
    return (pixels + FC_FLUID_BLOCK - 1) / FC_FLUID_BLOCK;
}

/* Grows the buffer to `blocks` entries; a new one replaces it, since the list is rewritten anyway. */
static fc_code reserve(fc_fluid_blocks *b, uint32_t blocks, fc_error *err)
{
    if (b->buffer && blocks <= b->capacity)
        return FC_OK;
    fc_fluid_blocks_release(b);
    uint64_t bytes = (HEADER_UINTS + (uint64_t)blocks) * sizeof(GLuint);
    glCreateBuffers(1, &b->buffer);
    glNamedBufferStorage(b->buffer, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    b->capacity = blocks;
    b->bytes = bytes;
    b->allocations++;
    return fc_gl_check("allocating the fluid block list", err);
}

fc_code fc_fluid_blocks_find(fc_fluid_blocks *b, const fc_render_target *depth, fc_error *err)
{
    uint32_t columns = blocks_along(depth->width), rows = blocks_along(depth->height);
    fc_code code = reserve(b, columns * rows, err);
    if (code != FC_OK)
        return code;
    const GLuint none_yet[HEADER_UINTS] = {0, 1, 1};
    glNamedBufferSubData(b->buffer, 0, sizeof none_yet, none_yet);
    glUseProgram(b->program);
    fc_render_target_uniform_size(b->program, LOC_SOURCE_SIZE, depth);
    glBindTextureUnit(BIND_DEPTH, depth->color);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_BLOCKS, b->buffer);
    glDispatchCompute((columns + GROUP_SIDE - 1) / GROUP_SIDE, (rows + GROUP_SIDE - 1) / GROUP_SIDE, 1);
    /* The list is read as dispatch arguments and by the filters' shaders. */
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    return fc_gl_check("listing the fluid blocks", err);
}

void fc_fluid_blocks_dispatch(const fc_fluid_blocks *b, GLuint binding)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b->buffer);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, b->buffer);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

void fc_fluid_blocks_tally(const fc_fluid_blocks *b, fc_gpu_memory *m)
{
    m->render_target_bytes += b->bytes;
    m->allocations += b->allocations;
}
