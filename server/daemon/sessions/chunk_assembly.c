/* chunk_assembly.c — see chunk_assembly.h. */
#include "sessions/chunk_assembly.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "monotonic.h"
#include "uploads/frame_pool.h"

void fc_chunk_assembly_init(fc_chunk_assembly *a, fc_frame_pool *pool)
{
    memset(a, 0, sizeof *a);
    a->pool = pool;
}

static void release(fc_frame_pool *pool, fc_frame_assembly *fa)
{
    if (fa->parts)
        for (uint32_t i = 0; i < fa->count; i++)
            fc_frame_pool_give_view(pool, &fa->parts[i]);
    free(fa->parts);
    free(fa->origins);
    memset(fa, 0, sizeof *fa);
}

void fc_chunk_assembly_free(fc_chunk_assembly *a)
{
    for (int i = 0; i < FC_ASSEMBLY_MAX_FRAMES; i++)
        release(a->pool, &a->frames[i]);
}

static fc_frame_assembly *find(fc_chunk_assembly *a, uint64_t frame_number)
{
    for (int i = 0; i < FC_ASSEMBLY_MAX_FRAMES; i++)
        if (a->frames[i].used && a->frames[i].frame_number == frame_number)
            return &a->frames[i];
    return NULL;
}

/* A free slot set up for the chunk's frame, or an error. */
static fc_code open_frame(fc_chunk_assembly *a, const fc_chunk *chunk, double deadline_ms,
                          fc_frame_assembly **out, fc_error *err)
{
    uint64_t number = chunk->header.frame_number;
    if (a->any_completed && number == a->last_completed)
        return fc_error_set(err, FC_ERR_DUPLICATE, "CHUNK: frame %llu is complete already",
                            (unsigned long long)number);
    if (a->any_completed && number < a->last_completed)
        return fc_error_set(err, FC_ERR_BAD_STATE, "CHUNK: frame %llu is older than frame %llu, complete already",
                            (unsigned long long)number, (unsigned long long)a->last_completed);
    fc_frame_assembly *fa = NULL;
    for (int i = 0; i < FC_ASSEMBLY_MAX_FRAMES && !fa; i++)
        if (!a->frames[i].used)
            fa = &a->frames[i];
    if (!fa)
        return fc_error_set(err, FC_ERR_LIMIT, "CHUNK: %d frames are being assembled already",
                            FC_ASSEMBLY_MAX_FRAMES);
    fa->parts = calloc(chunk->header.count, sizeof *fa->parts);
    fa->origins = calloc(chunk->header.count, sizeof *fa->origins);
    if (!fa->parts || !fa->origins) {
        release(a->pool, fa);
        return fc_error_set(err, FC_ERR_INTERNAL, "CHUNK: no memory for %u chunks", chunk->header.count);
    }
    fa->used = true;
    fa->frame_number = number;
    fa->count = chunk->header.count;
    fa->attributes = fc_frame_attributes(&chunk->part.frame);
    fa->deadline_ms = deadline_ms;
    fa->first_byte_ms = chunk->first_byte_ms;
    fa->last_byte_ms = chunk->received_ms;
    *out = fa;
    return FC_OK;
}

/* Checks a chunk against the frame it belongs to. */
static fc_code check_fit(const fc_frame_assembly *fa, const fc_chunk *chunk, uint64_t max_particles,
                         fc_error *err)
{
    const fc_chunk_header *h = &chunk->header;
    uint32_t attributes = fc_frame_attributes(&chunk->part.frame);
    if (h->count != fa->count)
        return fc_error_set(err, FC_ERR_INCONSISTENT, "CHUNK: frame %llu has K = %u chunks, this one says %u",
                            (unsigned long long)h->frame_number, fa->count, h->count);
    if (fa->parts[h->index].frame.count != 0)
        return fc_error_set(err, FC_ERR_DUPLICATE, "CHUNK: chunk %u of frame %llu arrived already", h->index,
                            (unsigned long long)h->frame_number);
    if (attributes != fa->attributes)
        return fc_error_set(err, FC_ERR_INCONSISTENT,
                            "CHUNK: attributes 0x%x differ from 0x%x of frame %llu's other chunks", attributes,
                            fa->attributes, (unsigned long long)h->frame_number);
    if (chunk->part.frame.count > max_particles - fa->particles)
        return fc_error_set(err, FC_ERR_LIMIT, "CHUNK: frame %llu would exceed the limit of %llu particles",
                            (unsigned long long)h->frame_number, (unsigned long long)max_particles);
    return FC_OK;
}

static void copy_part(fc_frame *whole, uint64_t at, const fc_frame *part)
{
    size_t n = (size_t)part->count;
    memcpy(whole->positions + 3 * at, part->positions, 3 * n * sizeof(float));
    if (whole->density)
        memcpy(whole->density + at, part->density, n * sizeof(float));
    if (whole->velocity)
        memcpy(whole->velocity + 3 * at, part->velocity, 3 * n * sizeof(float));
    if (whole->ids)
        memcpy(whole->ids + at, part->ids, n * sizeof(uint32_t));
    if (whole->radius)
        memcpy(whole->radius + at, part->radius, n * sizeof(float));
}

/* Concatenates the parts in index order into a block of out and frees the slot. */
static fc_code complete_frame(fc_chunk_assembly *a, fc_frame_assembly *fa, fc_assembled_frame *out, fc_error *err)
{
    double start = fc_monotonic_ms();
    /* Every part passed check_fit, so the total is within max_particles and its block size fits. */
    size_t size = fc_frame_block_size(fa->particles, fa->attributes);
    uint8_t *block = fc_frame_pool_take(a->pool, size);
    fc_code code = FC_OK;
    if (!block) {
        code = fc_error_set(err, FC_ERR_NOMEM, "CHUNK: no memory for a frame of %llu particles",
                            (unsigned long long)fa->particles);
    } else {
        fc_frame whole;
        fc_frame_point_into_block(&whole, block, fa->particles, fa->attributes);
        uint64_t at = 0;
        for (uint32_t i = 0; i < fa->count; i++) {
            copy_part(&whole, at, &fa->parts[i].frame);
            at += fa->parts[i].frame.count;
        }
        out->frame = (fc_frame_view){whole, block, size};
        out->frame_number = fa->frame_number;
        out->receive_ms = (float)(fa->last_byte_ms - fa->first_byte_ms);
        out->decode_ms = fa->decode_ms + (float)(fc_monotonic_ms() - start);
        if (!a->any_completed || fa->frame_number > a->last_completed)
            a->last_completed = fa->frame_number;
        a->any_completed = true;
    }
    release(a->pool, fa);
    return code;
}

fc_code fc_chunk_assembly_add(fc_chunk_assembly *a, fc_chunk *chunk, uint64_t max_particles, double now_ms,
                              double timeout_ms, bool *complete, fc_assembled_frame *out, fc_error *err)
{
    const fc_chunk_header *h = &chunk->header;
    *complete = false;
    if (h->count == 0 || h->count > FC_CHUNK_COUNT_MAX)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "CHUNK: K = %u is outside 1..%u", h->count,
                            FC_CHUNK_COUNT_MAX);
    if (h->index >= h->count)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "CHUNK: index %u is not below K = %u", h->index, h->count);
    fc_frame_assembly *fa = find(a, h->frame_number);
    bool opened = false;
    if (!fa) {
        fc_code code = open_frame(a, chunk, now_ms + timeout_ms, &fa, err);
        if (code != FC_OK)
            return code;
        opened = true;
    }
    fc_code code = check_fit(fa, chunk, max_particles, err);
    if (code != FC_OK) {
        if (opened)
            release(a->pool, fa);
        return code;
    }
    fa->parts[h->index] = chunk->part;
    memset(&chunk->part, 0, sizeof chunk->part);
    fa->origins[h->index] = chunk->origin;
    fa->particles += fa->parts[h->index].frame.count;
    fa->received++;
    fa->decode_ms += chunk->decode_ms;
    if (chunk->first_byte_ms < fa->first_byte_ms)
        fa->first_byte_ms = chunk->first_byte_ms;
    if (chunk->received_ms > fa->last_byte_ms)
        fa->last_byte_ms = chunk->received_ms;
    if (fa->received < fa->count)
        return FC_OK;
    code = complete_frame(a, fa, out, err);
    *complete = code == FC_OK;
    return code;
}

double fc_chunk_assembly_next_deadline(const fc_chunk_assembly *a)
{
    double next = -1.0;
    for (int i = 0; i < FC_ASSEMBLY_MAX_FRAMES; i++)
        if (a->frames[i].used && (next < 0.0 || a->frames[i].deadline_ms < next))
            next = a->frames[i].deadline_ms;
    return next;
}

static void report_incomplete(const fc_frame_assembly *fa,
                              void (*report)(const fc_chunk_origin *origin, const fc_error *err, void *data),
                              void *data)
{
    fc_error err;
    fc_error_set(&err, FC_ERR_INCOMPLETE, "frame %llu: only %u of its %u chunks arrived before the chunk timeout",
                 (unsigned long long)fa->frame_number, fa->received, fa->count);
    for (uint32_t i = 0; i < fa->count; i++)
        if (fa->parts[i].frame.count != 0 && fa->origins[i].producer)
            report(&fa->origins[i], &err, data);
}

void fc_chunk_assembly_expire(fc_chunk_assembly *a, double now_ms,
                              void (*report)(const fc_chunk_origin *origin, const fc_error *err, void *data),
                              void *data)
{
    for (int i = 0; i < FC_ASSEMBLY_MAX_FRAMES; i++) {
        fc_frame_assembly *fa = &a->frames[i];
        if (!fa->used || fa->deadline_ms > now_ms)
            continue;
        report_incomplete(fa, report, data);
        release(a->pool, fa);
    }
}

void fc_chunk_assembly_forget(fc_chunk_assembly *a, const fc_session_member *producer)
{
    for (int i = 0; i < FC_ASSEMBLY_MAX_FRAMES; i++)
        for (uint32_t k = 0; a->frames[i].used && k < a->frames[i].count; k++)
            if (a->frames[i].origins[k].producer == producer)
                a->frames[i].origins[k].producer = NULL;
}
