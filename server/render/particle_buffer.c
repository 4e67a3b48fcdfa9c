/* particle_buffer.c — particle positions (and radii) on the GPU. */
#include "particle_buffer.h"

#include <string.h>

#include "density_order.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "gl_util.h"

#define POSITION_STRIDE (3 * sizeof(float))
#define RADIUS_STRIDE sizeof(float)
/* Storage buffer binding of the ratios in sphere_shape.vert.glsl and ellipsoid_shape.vert.glsl. */
enum { BIND_RADIUS_RATIOS = 7 };

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

static void release_radii(fc_particle_buffer *pb)
{
    if (pb->mapped_radii)
        glUnmapNamedBuffer(pb->radii);
    glDeleteBuffers(1, &pb->radii);
    pb->mapped_radii = NULL;
    pb->radii = 0;
    pb->radii_capacity = 0;
}

void fc_particle_buffer_destroy(fc_particle_buffer *pb)
{
    release_buffer(pb);
    release_radii(pb);
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

/* A radius buffer of `count` floats, persistently mapped like the positions'. */
static fc_code grow_radii(fc_particle_buffer *pb, uint64_t count, fc_error *err)
{
    release_radii(pb);
    pb->allocations++;
    GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    /* The compute splat reads it through a texture buffer (fc_gl_non_pot). */
    GLsizeiptr bytes = (GLsizeiptr)fc_gl_non_pot(count * RADIUS_STRIDE);
    glCreateBuffers(1, &pb->radii);
    glNamedBufferStorage(pb->radii, bytes, NULL, flags);
    fc_code code = fc_gl_check("allocating the particle radius buffer", err);
    if (code == FC_OK && !(pb->mapped_radii = glMapNamedBufferRange(pb->radii, 0, bytes, flags)))
        code = fc_gl_failure("mapping the particle radius buffer", err);
    if (code != FC_OK) {
        release_radii(pb);
        return code;
    }
    pb->radii_capacity = count;
    return FC_OK;
}

fc_code fc_particle_buffer_reserve(fc_particle_buffer *pb, uint64_t count, bool radii, fc_error *err)
{
    pb->count = 0;
    pb->has_radii = false;
    /* Waiting for every command so far covers the draws that read the frame
     * about to be overwritten, here and in the other mapped buffers, also
     * when this one is replaced. */
    fc_code code = fc_gl_wait_until_done("waiting for the last frame's draws", err);
    if (code == FC_OK && count > pb->capacity)
        code = grow(pb, count, err);
    /* Grown to the positions' capacity, so frames with radii of any size up to it allocate nothing more. */
    if (code == FC_OK && radii && count > pb->radii_capacity)
        code = grow_radii(pb, pb->capacity, err);
    return code;
}

fc_code fc_particle_buffer_measure_radii(fc_particle_buffer *pb, const fc_frame *frame, fc_error *err)
{
    pb->has_radii = false;
    if (!frame->radius || frame->count == 0)
        return FC_OK;
    float median = 0.0f;
    fc_code code = fc_frame_median_radius(frame, &median, err);
    if (code != FC_OK)
        return code;
    pb->radius_median = median;
    pb->has_radii = median > 0.0f;
    return FC_OK;
}

/* Bounds kept in locals while copying: through pb they could alias the
 * mapped floats, and the compiler would store and reload them per point. */
typedef struct bounds {
    float lo[3], hi[3];
} bounds;

static bounds bounds_of_point(const float p[3])
{
    return (bounds){{p[0], p[1], p[2]}, {p[0], p[1], p[2]}};
}

static void include_point(bounds *b, const float p[3])
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = p[k] < b->lo[k] ? p[k] : b->lo[k];
        b->hi[k] = p[k] > b->hi[k] ? p[k] : b->hi[k];
    }
}

/* Positions into `to`, slot by slot: from order[slot] when there is an order,
 * else from the slot itself. */
static bounds copy_positions(float *to, const float *positions, const uint32_t *order, uint64_t count)
{
    bounds b = bounds_of_point(positions + 3 * (size_t)(order ? order[0] : 0));
    for (uint64_t slot = 0; slot < count; slot++) {
        if (order && slot + FC_DRAW_ORDER_PREFETCH < count)
            __builtin_prefetch(positions + 3 * (size_t)order[slot + FC_DRAW_ORDER_PREFETCH]);
        const float *from = positions + 3 * (size_t)(order ? order[slot] : slot);
        float p[3] = {from[0], from[1], from[2]};
        memcpy(to + 3 * slot, p, sizeof p);
        include_point(&b, p);
    }
    return b;
}

/* Each particle's ratio to the median, slot by slot; returns the largest.
 * Equal radii give exactly 1 (x / x is exact in IEEE arithmetic). */
static float copy_ratios(float *to, const float *radius, const uint32_t *order, uint64_t count, float median)
{
    float largest = 0.0f;
    for (uint64_t slot = 0; slot < count; slot++) {
        float ratio = radius[order ? order[slot] : slot] / median;
        to[slot] = ratio;
        largest = ratio > largest ? ratio : largest;
    }
    return largest;
}

/* One pass: each position is read once, written once into the mapped
 * buffer and bounded on the way. */
void fc_particle_buffer_fill(fc_particle_buffer *pb, const fc_frame *frame, const uint32_t *order)
{
    bounds b = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    if (frame->count > 0)
        b = copy_positions(pb->mapped, frame->positions, order, frame->count);
    if (pb->has_radii && frame->radius && frame->count <= pb->radii_capacity)
        pb->radius_ratio_max = copy_ratios(pb->mapped_radii, frame->radius, order, frame->count, pb->radius_median);
    else
        pb->has_radii = false;
    memcpy(pb->lo, b.lo, sizeof b.lo);
    memcpy(pb->hi, b.hi, sizeof b.hi);
    pb->count = frame->count;
    pb->generation++;
}

fc_code fc_particle_buffer_upload(fc_particle_buffer *pb, const fc_frame *frame, fc_error *err)
{
    fc_code code = fc_particle_buffer_reserve(pb, frame->count, frame->radius != NULL, err);
    if (code == FC_OK)
        code = fc_particle_buffer_measure_radii(pb, frame, err);
    if (code == FC_OK)
        fc_particle_buffer_fill(pb, frame, NULL);
    return code;
}

void fc_particle_buffer_bind(const fc_particle_buffer *pb, bool per_instance)
{
    glVertexArrayBindingDivisor(pb->vertex_array, 0, per_instance ? 1 : 0);
    glBindVertexArray(pb->vertex_array);
}

void fc_particle_buffer_bind_radii(const fc_particle_buffer *pb)
{
    if (pb->sized)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_RADIUS_RATIOS, pb->radii);
}

float fc_particle_buffer_largest_radius(const fc_particle_buffer *pb, float radius)
{
    return pb->sized ? radius * pb->radius_ratio_max : radius;
}

void fc_particle_buffer_tally(const fc_particle_buffer *pb, fc_gpu_memory *m)
{
    m->particle_bytes += pb->capacity * POSITION_STRIDE + pb->radii_capacity * RADIUS_STRIDE;
    m->allocations += pb->allocations;
}
