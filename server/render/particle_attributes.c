/* particle_attributes.c — per-particle records and noise amplitudes for the shading passes. */
#include "particle_attributes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "gl_util.h"

/* A zero-sized buffer cannot be bound; an empty frame keeps these. */
#define MIN_GPU_PARTICLES 1
#define MAPPED_FLAGS (GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT)

static void release_buffer(GLuint *buffer, void **mapped)
{
    if (*mapped)
        glUnmapNamedBuffer(*buffer);
    glDeleteBuffers(1, buffer);
    *buffer = 0;
    *mapped = NULL;
}

static void release_gpu(fc_particle_attributes *a)
{
    release_buffer(&a->records, (void **)&a->mapped_records);
    release_buffer(&a->amplitudes, (void **)&a->mapped_amplitudes);
    a->gpu_capacity = 0;
    a->plain_records = 0;
    a->calm_amplitudes = 0;
}

/* A coherent persistently mapped buffer: writes need no flush. */
static fc_code map_new_buffer(fc_particle_attributes *a, GLsizeiptr bytes, GLuint *buffer, void **mapped,
                              fc_error *err)
{
    a->gpu_allocations++;
    glCreateBuffers(1, buffer);
    glNamedBufferStorage(*buffer, bytes, NULL, MAPPED_FLAGS);
    fc_code code = fc_gl_check("allocating the particle attributes", err);
    if (code == FC_OK && !(*mapped = glMapNamedBufferRange(*buffer, 0, bytes, MAPPED_FLAGS)))
        code = fc_gl_failure("mapping the particle attributes", err);
    return code;
}

/* Both buffers for `count` particles; the old ones are dropped first so the
 * two generations never occupy GPU memory at once. */
static fc_code grow_gpu(fc_particle_attributes *a, uint64_t count, fc_error *err)
{
    release_gpu(a);
    fc_code code = map_new_buffer(a, (GLsizeiptr)(count * sizeof(fc_particle_record)), &a->records,
                                  (void **)&a->mapped_records, err);
    if (code == FC_OK)
        code = map_new_buffer(a, (GLsizeiptr)(count * sizeof(float)), &a->amplitudes,
                              (void **)&a->mapped_amplitudes, err);
    if (code != FC_OK) {
        release_gpu(a);
        return code;
    }
    a->gpu_capacity = count;
    return FC_OK;
}

fc_code fc_particle_attributes_create(fc_particle_attributes *a, fc_error *err)
{
    *a = (fc_particle_attributes){0};
    return grow_gpu(a, MIN_GPU_PARTICLES, err);
}

void fc_particle_attributes_destroy(fc_particle_attributes *a)
{
    release_gpu(a);
    fc_density_order_free(&a->order);
    free(a->frame_amplitudes);
    *a = (fc_particle_attributes){0};
}

static uint32_t frame_index(const fc_particle_attributes *a, uint64_t slot)
{
    return a->by_density ? a->order.order[slot] : (uint32_t)slot;
}

static float speed_of(const float *v)
{
    return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* A frame of positions alone in its own order: records (slot, 0), which the
 * buffer may already hold from an earlier frame. */
static void write_plain_records(fc_particle_attributes *a, uint64_t count)
{
    for (uint64_t slot = a->plain_records; slot < count; slot++)
        a->mapped_records[slot] = (fc_particle_record){.id = (uint32_t)slot, .speed = 0.0f};
    if (count > a->plain_records)
        a->plain_records = count;
}

static void prefetch_particle(const fc_frame *frame, uint32_t i)
{
    if (frame->ids)
        __builtin_prefetch(frame->ids + i);
    if (frame->velocity)
        __builtin_prefetch(frame->velocity + 3 * (size_t)i);
}

static void write_records(fc_particle_attributes *a, const fc_frame *frame)
{
    if (!frame->ids && !frame->velocity && !a->by_density) {
        write_plain_records(a, frame->count);
        return;
    }
    for (uint64_t slot = 0; slot < frame->count; slot++) {
        if (a->by_density && slot + FC_DRAW_ORDER_PREFETCH < frame->count)
            prefetch_particle(frame, a->order.order[slot + FC_DRAW_ORDER_PREFETCH]);
        uint32_t i = frame_index(a, slot);
        a->mapped_records[slot] = (fc_particle_record){
            .id = frame->ids ? frame->ids[i] : i,
            .speed = frame->velocity ? speed_of(frame->velocity + 3 * (size_t)i) : 0.0f,
        };
    }
    a->plain_records = 0;
}

fc_code fc_particle_attributes_upload(fc_particle_attributes *a, const fc_frame *frame, fc_error *err)
{
    a->count = 0;
    a->by_density = false;
    a->reorderable = frame->count > 0;
    a->frame_amplitudes_set = false;
    if (frame->count > a->gpu_capacity) {
        fc_code code = grow_gpu(a, frame->count, err);
        if (code != FC_OK)
            return code;
    }
    write_records(a, frame);
    a->count = frame->count;
    a->amplitudes_set = false;
    return FC_OK;
}

/* Amplitudes (frame order) into the mapped buffer, in draw order. */
static void write_amplitudes(fc_particle_attributes *a, const float *amplitude)
{
    for (uint64_t slot = 0; slot < a->count; slot++) {
        if (a->by_density && slot + FC_DRAW_ORDER_PREFETCH < a->count)
            __builtin_prefetch(amplitude + a->order.order[slot + FC_DRAW_ORDER_PREFETCH]);
        a->mapped_amplitudes[slot] = amplitude[frame_index(a, slot)];
    }
    a->calm_amplitudes = 0;
}

fc_code fc_particle_attributes_order_by_density(fc_particle_attributes *a, const fc_frame *frame, const float *keys,
                                                uint32_t classes, fc_error *err)
{
    if (!a->reorderable || (a->by_density && a->ordered_classes == classes))
        return FC_OK;
    fc_code code = fc_density_order_sort(&a->order, keys, frame->count, err);
    if (code == FC_OK)
        code = fc_gl_wait_until_done("waiting for the draws reading the particles in frame order", err);
    if (code != FC_OK) {
        a->by_density = false;   /* the order's arrays were rewritten */
        return code;
    }
    a->density_sorts++;
    a->by_density = true;
    a->ordered_classes = classes;
    write_records(a, frame);
    /* Calm amplitudes (all 1, or still to be settled) read the same in any order. */
    if (a->frame_amplitudes_set)
        write_amplitudes(a, a->frame_amplitudes);
    return FC_OK;
}

const uint32_t *fc_particle_attributes_draw_order(const fc_particle_attributes *a)
{
    return a->by_density ? a->order.order : NULL;
}

uint64_t fc_particle_attributes_surface_count(const fc_particle_attributes *a, float density_threshold)
{
    if (!a->by_density || !(density_threshold > 0.0f))
        return a->count;
    return fc_density_order_count_at_least(&a->order, a->count, density_threshold);
}

/* Keeps a frame-order copy of the amplitudes of a frame a render may still
 * put in density order, or in another (a render asking for other classes). */
static fc_code keep_for_reorder(fc_particle_attributes *a, const float *amplitude, fc_error *err)
{
    a->frame_amplitudes_set = false;
    if (!a->reorderable)
        return FC_OK;
    if (a->count > a->frame_amplitude_capacity) {
        float *grown = realloc(a->frame_amplitudes, a->count * sizeof *grown);
        if (!grown)
            return fc_error_set(err, FC_ERR_NOMEM, "no memory to keep the amplitudes of %llu particles",
                                (unsigned long long)a->count);
        a->frame_amplitudes = grown;
        a->frame_amplitude_capacity = a->count;
    }
    memcpy(a->frame_amplitudes, amplitude, a->count * sizeof *amplitude);
    a->frame_amplitudes_set = true;
    return FC_OK;
}

fc_code fc_particle_attributes_set_amplitudes(fc_particle_attributes *a, const float *amplitude, fc_error *err)
{
    fc_code code = keep_for_reorder(a, amplitude, err);
    if (code == FC_OK)
        code = fc_gl_wait_until_done("waiting for the draws reading the amplitudes", err);
    if (code != FC_OK)
        return code;
    write_amplitudes(a, amplitude);
    a->amplitudes_set = true;
    return FC_OK;
}

void fc_particle_attributes_settle(fc_particle_attributes *a)
{
    if (a->amplitudes_set)
        return;
    for (uint64_t slot = a->calm_amplitudes; slot < a->count; slot++)
        a->mapped_amplitudes[slot] = 1.0f;
    if (a->count > a->calm_amplitudes)
        a->calm_amplitudes = a->count;
    a->amplitudes_set = true;
}

void fc_particle_attributes_bind(const fc_particle_attributes *a)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FC_PARTICLE_RECORDS_BINDING, a->records);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FC_PARTICLE_AMPLITUDES_BINDING, a->amplitudes);
}

void fc_particle_attributes_tally(const fc_particle_attributes *a, fc_gpu_memory *m)
{
    m->particle_bytes += a->gpu_capacity * (sizeof(fc_particle_record) + sizeof(float));
    m->allocations += a->gpu_allocations;
}
