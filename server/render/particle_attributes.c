/* particle_attributes.c — per-particle records for the shading passes. */
#include "particle_attributes.h"

#include <math.h>
#include <stdlib.h>

#include "fc_error.h"
#include "gl_util.h"

/* A zero-sized buffer cannot be bound; an empty frame keeps this one. */
#define MIN_GPU_RECORDS 1

static fc_code grow_gpu(fc_particle_attributes *a, uint64_t count, fc_error *err)
{
    glDeleteBuffers(1, &a->buffer);
    a->buffer = 0;
    a->gpu_capacity = 0;
    a->gpu_allocations++;
    glCreateBuffers(1, &a->buffer);
    glNamedBufferStorage(a->buffer, (GLsizeiptr)(count * sizeof(fc_particle_record)), NULL,
                         GL_DYNAMIC_STORAGE_BIT);
    fc_code code = fc_gl_check("allocating the particle records", err);
    if (code == FC_OK)
        a->gpu_capacity = count;
    return code;
}

fc_code fc_particle_attributes_create(fc_particle_attributes *a, fc_error *err)
{
    *a = (fc_particle_attributes){0};
    return grow_gpu(a, MIN_GPU_RECORDS, err);
}

void fc_particle_attributes_destroy(fc_particle_attributes *a)
{
    glDeleteBuffers(1, &a->buffer);
    free(a->records);
    free(a->positions);
    fc_density_order_free(&a->order);
    *a = (fc_particle_attributes){0};
}

static fc_code out_of_memory(uint64_t count, fc_error *err)
{
    return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the attributes of %llu particles",
                        (unsigned long long)count);
}

/* Room for `count` records, and positions when the draw order differs from the frame's. */
static fc_code reserve(fc_particle_attributes *a, uint64_t count, bool reordered, fc_error *err)
{
    if (count > a->record_capacity) {
        fc_particle_record *records = realloc(a->records, count * sizeof *records);
        if (!records)
            return out_of_memory(count, err);
        a->records = records;
        a->record_capacity = count;
    }
    if (reordered && count > a->position_capacity) {
        float *positions = realloc(a->positions, count * 3 * sizeof *positions);
        if (!positions)
            return out_of_memory(count, err);
        a->positions = positions;
        a->position_capacity = count;
    }
    return FC_OK;
}

static uint32_t frame_index(const fc_particle_attributes *a, uint64_t slot)
{
    return a->by_density ? a->order.order[slot] : (uint32_t)slot;
}

static void fill_records(fc_particle_attributes *a, const fc_frame *frame)
{
    for (uint64_t slot = 0; slot < frame->count; slot++) {
        uint32_t i = frame_index(a, slot);
        fc_particle_record *r = &a->records[slot];
        r->id = frame->ids ? frame->ids[i] : i;
        const float *v = frame->velocity ? frame->velocity + 3 * (size_t)i : NULL;
        r->speed = v ? sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) : 0.0f;
        r->amplitude = 1.0f;
        r->density = frame->density ? frame->density[i] : 0.0f;
    }
}

static void reorder_positions(fc_particle_attributes *a, const fc_frame *frame)
{
    for (uint64_t slot = 0; slot < frame->count; slot++) {
        const float *from = frame->positions + 3 * (size_t)a->order.order[slot];
        float *to = a->positions + 3 * slot;
        to[0] = from[0];
        to[1] = from[1];
        to[2] = from[2];
    }
}

static fc_code send_records(fc_particle_attributes *a, fc_error *err)
{
    if (a->count > a->gpu_capacity) {
        fc_code code = grow_gpu(a, a->count, err);
        if (code != FC_OK)
            return code;
    }
    if (a->count > 0)
        glNamedBufferSubData(a->buffer, 0, (GLsizeiptr)(a->count * sizeof(fc_particle_record)), a->records);
    return fc_gl_check("uploading the particle records", err);
}

fc_code fc_particle_attributes_upload(fc_particle_attributes *a, const fc_frame *frame, const float **positions,
                                      fc_error *err)
{
    a->count = 0;
    a->by_density = frame->density != NULL && frame->count > 0;
    fc_code code = reserve(a, frame->count, a->by_density, err);
    if (code == FC_OK && a->by_density)
        code = fc_density_order_sort(&a->order, frame->density, frame->count, err);
    if (code != FC_OK)
        return code;
    fill_records(a, frame);
    *positions = frame->positions;
    if (a->by_density) {
        reorder_positions(a, frame);
        *positions = a->positions;
    }
    a->count = frame->count;
    return send_records(a, err);
}

uint64_t fc_particle_attributes_surface_count(const fc_particle_attributes *a, float density_threshold)
{
    if (!a->by_density || !(density_threshold > 0.0f))
        return a->count;
    /* Densities descend along the draw order: find the first below the threshold. */
    uint64_t lo = 0, hi = a->count;
    while (lo < hi) {
        uint64_t mid = lo + (hi - lo) / 2;
        if (a->records[mid].density >= density_threshold)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

fc_code fc_particle_attributes_set_amplitudes(fc_particle_attributes *a, const float *amplitude, fc_error *err)
{
    for (uint64_t slot = 0; slot < a->count; slot++)
        a->records[slot].amplitude = amplitude[frame_index(a, slot)];
    return send_records(a, err);
}

void fc_particle_attributes_bind(const fc_particle_attributes *a)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FC_PARTICLE_RECORDS_BINDING, a->buffer);
}

void fc_particle_attributes_tally(const fc_particle_attributes *a, fc_gpu_memory *m)
{
    m->particle_bytes += a->gpu_capacity * sizeof(fc_particle_record);
    m->allocations += a->gpu_allocations;
}
