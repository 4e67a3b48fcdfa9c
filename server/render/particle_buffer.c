/* particle_buffer.c — particle positions on the GPU. */
#include "particle_buffer.h"

#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "gl_util.h"

#define POSITION_STRIDE (3 * sizeof(float))

fc_code fc_particle_buffer_create(fc_particle_buffer *pb, fc_error *err)
{
    *pb = (fc_particle_buffer){0};
    glCreateVertexArrays(1, &pb->vertex_array);
    glEnableVertexArrayAttrib(pb->vertex_array, 0);
    glVertexArrayAttribFormat(pb->vertex_array, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(pb->vertex_array, 0, 0);
    return fc_gl_check("creating the particle vertex array", err);
}

static void release_buffer(fc_particle_buffer *pb)
{
    if (pb->mapped)
        glUnmapNamedBuffer(pb->buffer);
    glDeleteBuffers(1, &pb->buffer);
    pb->mapped = NULL;
    pb->buffer = 0;
    pb->capacity = 0;
}

void fc_particle_buffer_destroy(fc_particle_buffer *pb)
{
    release_buffer(pb);
    glDeleteVertexArrays(1, &pb->vertex_array);
    *pb = (fc_particle_buffer){0};
}

/* A new buffer of `count` particles; the old one is dropped first so both
 * never occupy GPU memory at once. Coherent mapping: writes need no flush. */
static fc_code grow(fc_particle_buffer *pb, uint64_t count, fc_error *err)
{
    release_buffer(pb);
    pb->allocations++;
    /* Draws count vertices and instances in a GLsizei. */
    if (count > (uint64_t)INT32_MAX)
        return fc_error_set(err, FC_ERR_RENDER, "%llu particles exceed the %d one draw call can render",
                            (unsigned long long)count, INT32_MAX);
    GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    GLsizeiptr bytes = (GLsizeiptr)(count * POSITION_STRIDE);
    glCreateBuffers(1, &pb->buffer);
    glNamedBufferStorage(pb->buffer, bytes, NULL, flags);
    fc_code code = fc_gl_check("allocating the particle buffer", err);
    if (code == FC_OK && !(pb->mapped = glMapNamedBufferRange(pb->buffer, 0, bytes, flags)))
        code = fc_gl_failure("mapping the particle buffer", err);
    if (code != FC_OK) {
        release_buffer(pb);
        return code;
    }
    glVertexArrayVertexBuffer(pb->vertex_array, 0, pb->buffer, 0, POSITION_STRIDE);
    pb->capacity = count;
    return FC_OK;
}

fc_code fc_particle_buffer_upload(fc_particle_buffer *pb, const fc_frame *frame, fc_error *err)
{
    pb->count = 0;
    /* Waiting for every command so far covers the draws that read the frame about to be overwritten. */
    fc_code code = frame->count > pb->capacity ? grow(pb, frame->count, err)
                                               : fc_gl_wait_until_done("waiting for the last frame's draws", err);
    if (code != FC_OK)
        return code;
    if (frame->count > 0) {
        memcpy(pb->mapped, frame->positions, frame->count * POSITION_STRIDE);
        fc_frame_bounds(frame, pb->lo, pb->hi);
    } else {
        for (int i = 0; i < 3; i++)
            pb->lo[i] = pb->hi[i] = 0.0f;
    }
    code = fc_gl_check("uploading particles", err);
    if (code == FC_OK)
        pb->count = frame->count;
    return code;
}

void fc_particle_buffer_bind(const fc_particle_buffer *pb, bool per_instance)
{
    glVertexArrayBindingDivisor(pb->vertex_array, 0, per_instance ? 1 : 0);
    glBindVertexArray(pb->vertex_array);
}


void fc_particle_buffer_tally(const fc_particle_buffer *pb, fc_gpu_memory *m)
{
    m->particle_bytes += pb->capacity * POSITION_STRIDE;
    m->allocations += pb->allocations;
}
