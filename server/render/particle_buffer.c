/* particle_buffer.c — particle positions on the GPU. */
#include "particle_buffer.h"

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

void fc_particle_buffer_destroy(fc_particle_buffer *pb)
{
    glDeleteVertexArrays(1, &pb->vertex_array);
    glDeleteBuffers(1, &pb->buffer);
    *pb = (fc_particle_buffer){0};
}

/* A new buffer of `count` particles; the old one is dropped first so both
 * never occupy GPU memory at once. */
static fc_code grow(fc_particle_buffer *pb, uint64_t count, fc_error *err)
{
    glDeleteBuffers(1, &pb->buffer);
    pb->buffer = 0;
    pb->capacity = 0;
    /* Draws count vertices and instances in a GLsizei. */
    if (count > (uint64_t)INT32_MAX)
        return fc_error_set(err, FC_ERR_RENDER, "%llu particles exceed the %d one draw call can render",
                            (unsigned long long)count, INT32_MAX);
    glCreateBuffers(1, &pb->buffer);
    glNamedBufferStorage(pb->buffer, (GLsizeiptr)(count * POSITION_STRIDE), NULL, GL_DYNAMIC_STORAGE_BIT);
    fc_code code = fc_gl_check("allocating the particle buffer", err);
    if (code != FC_OK)
        return code;
    glVertexArrayVertexBuffer(pb->vertex_array, 0, pb->buffer, 0, POSITION_STRIDE);
    pb->capacity = count;
    return FC_OK;
}

fc_code fc_particle_buffer_upload(fc_particle_buffer *pb, const fc_frame *frame, fc_error *err)
{
    pb->count = 0;
    if (frame->count > pb->capacity) {
        fc_code code = grow(pb, frame->count, err);
        if (code != FC_OK)
            return code;
    }
    if (frame->count > 0) {
        glNamedBufferSubData(pb->buffer, 0, (GLsizeiptr)(frame->count * POSITION_STRIDE), frame->positions);
        fc_frame_bounds(frame, pb->lo, pb->hi);
    } else {
        for (int i = 0; i < 3; i++)
            pb->lo[i] = pb->hi[i] = 0.0f;
    }
    fc_code code = fc_gl_check("uploading particles", err);
    if (code == FC_OK)
        pb->count = frame->count;
    return code;
}

void fc_particle_buffer_bind(const fc_particle_buffer *pb, bool per_instance)
{
    glVertexArrayBindingDivisor(pb->vertex_array, 0, per_instance ? 1 : 0);
    glBindVertexArray(pb->vertex_array);
}

