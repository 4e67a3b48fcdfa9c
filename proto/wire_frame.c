/* wire_frame.c — the FRAME message: particle arrays, one after the other. */
#include "wire.h"

#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "wire_frame_io.h"

#define FRAME_FIXED_SIZE 16u
#define FRAME_ATTR_ALL FC_ATTR_ALL

/* The particle arrays of m in wire order. */
static size_t frame_arrays(const fc_frame *m, size_t count, fc_wire_span arrays[FC_WIRE_FRAME_ARRAYS])
{
    size_t n = 0;
    arrays[n++] = (fc_wire_span){m->positions, 3 * count * sizeof(float)};
    if (m->density)
        arrays[n++] = (fc_wire_span){m->density, count * sizeof(float)};
    if (m->velocity)
        arrays[n++] = (fc_wire_span){m->velocity, 3 * count * sizeof(float)};
    if (m->ids)
        arrays[n++] = (fc_wire_span){m->ids, count * sizeof(uint32_t)};
    if (m->radius)
        arrays[n++] = (fc_wire_span){m->radius, count * sizeof(float)};
    return n;
}

fc_code fc_wire_write_frame_parts(fc_buf *out, uint32_t request_id, const fc_frame *m,
                                  fc_wire_span arrays[FC_WIRE_FRAME_ARRAYS], size_t *array_count, fc_error *err)
{
    *array_count = 0;
    if (m->count == 0 || !m->positions)
        return fc_error_set(err, FC_ERR_USAGE, "a FRAME needs at least one particle");
    uint32_t attributes = fc_frame_attributes(m);
    uint64_t stride = fc_frame_particle_bytes(attributes);
    fc_code code = wire_check_length(FRAME_FIXED_SIZE, m->count, stride, "FRAME", err);
    if (code != FC_OK)
        return code;
    /* The check above bounds count below 2^32 / 12, so every size_t product fits. */
    size_t count = (size_t)m->count;
    uint32_t length = (uint32_t)(FRAME_FIXED_SIZE + count * stride);
    size_t start = wire_begin_message_part(out, FC_MSG_FRAME, request_id, length,
                                           WIRE_HOST_IS_LITTLE_ENDIAN ? FRAME_FIXED_SIZE : length);
    wire_put_u64(out, m->count);
    wire_put_u32(out, attributes);
    wire_put_u32(out, 0); /* reserved */
    fc_wire_span spans[FC_WIRE_FRAME_ARRAYS];
    size_t n = frame_arrays(m, count, spans);
    for (size_t i = 0; i < n; i++) {
        if (WIRE_HOST_IS_LITTLE_ENDIAN)
            arrays[i] = spans[i];
        else
            wire_put_u32_array(out, spans[i].data, spans[i].size / 4);
    }
    code = wire_end_message(out, start, err);
    if (code == FC_OK && WIRE_HOST_IS_LITTLE_ENDIAN)
        *array_count = n;
    return code;
}

fc_code fc_wire_write_frame(fc_buf *out, uint32_t request_id, const fc_frame *m, fc_error *err)
{
    fc_wire_span arrays[FC_WIRE_FRAME_ARRAYS];
    size_t n, start = out->len;
    fc_code code = fc_wire_write_frame_parts(out, request_id, m, arrays, &n, err);
    if (code != FC_OK)
        return code;
    /* One reservation for the arrays, so they are not regrown piecemeal. */
    size_t bytes = 0;
    for (size_t i = 0; i < n; i++)
        bytes += arrays[i].size;
    fc_buf_reserve(out, bytes);
    for (size_t i = 0; i < n; i++)
        wire_put_bytes(out, arrays[i].data, arrays[i].size);
    return wire_end_message(out, start, err);
}

/* Checks the fixed part in the order PROTOCOL.md gives, before anything is allocated. */
static fc_code check_frame_layout(wire_reader *r, uint64_t count, uint32_t attributes, uint32_t reserved,
                                  uint64_t max_particles)
{
    if (attributes & ~(uint32_t)FRAME_ATTR_ALL)
        wire_fail(r, FC_ERR_MALFORMED, "unknown attribute bits 0x%x", attributes & ~(uint32_t)FRAME_ATTR_ALL);
    else if (reserved != 0)
        wire_fail(r, FC_ERR_MALFORMED, "reserved field is %u, must be 0", reserved);
    else if (count == 0)
        wire_fail(r, FC_ERR_INVALID_VALUE, "a frame needs at least one particle");
    else if (count > max_particles)
        wire_fail(r, FC_ERR_LIMIT, "%llu particles exceed the limit of %llu", (unsigned long long)count,
                  (unsigned long long)max_particles);
    else if (count > wire_remaining(r) / fc_frame_particle_bytes(attributes) ||
             count * fc_frame_particle_bytes(attributes) != wire_remaining(r))
        wire_fail(r, FC_ERR_MALFORMED, "%llu particles of %llu bytes do not match the %zu bytes that follow",
                  (unsigned long long)count, (unsigned long long)fc_frame_particle_bytes(attributes), wire_remaining(r));
    return r->code;
}

/* Reads and checks the fixed fields; the particles' bytes follow at the reader. */
static fc_code read_frame_head(wire_reader *r, uint64_t max_particles, uint64_t *count, uint32_t *attributes)
{
    *count = wire_get_u64(r, "count");
    *attributes = wire_get_u32(r, "attributes");
    uint32_t reserved = wire_get_u32(r, "reserved");
    if (r->code == FC_OK)
        check_frame_layout(r, *count, *attributes, reserved, max_particles);
    return r->code;
}

fc_code fc_wire_read_frame(const uint8_t *p, size_t n, uint64_t max_particles, fc_frame *m, fc_error *err)
{
    wire_reader r = wire_reader_start(p, n, "FRAME", err);
    uint64_t count;
    uint32_t attributes;
    if (read_frame_head(&r, max_particles, &count, &attributes) != FC_OK)
        return r.code;

    fc_frame frame;
    fc_code code = fc_frame_alloc(&frame, count, attributes, err);
    if (code != FC_OK)
        return code;
    /* The layout check proved count * stride == the bytes left, so count fits size_t. */
    wire_get_f32_array(&r, frame.positions, 3 * (size_t)count, "positions");
    code = wire_get_frame_attributes(&r, &frame, err);
    if (code != FC_OK) {
        fc_frame_free(&frame);
        return code;
    }
    *m = frame;
    return FC_OK;
}

fc_code fc_wire_view_frame(uint8_t *p, size_t n, uint64_t max_particles, fc_frame *view, fc_error *err)
{
    if ((uintptr_t)p % sizeof(float) != 0)
        return fc_error_set(err, FC_ERR_USAGE, "FRAME: a payload viewed in place must be 4-byte aligned");
    wire_reader r = wire_reader_start(p, n, "FRAME", err);
    uint64_t count;
    uint32_t attributes;
    if (read_frame_head(&r, max_particles, &count, &attributes) != FC_OK)
        return r.code;
    uint8_t *arrays = p + FRAME_FIXED_SIZE;
    fc_frame frame;
    fc_frame_point_into_block(&frame, arrays, count, attributes);
    /* The layout check proved count * stride == the bytes left, so this fits size_t. */
    wire_words_to_host(arrays, fc_frame_block_size(count, attributes) / 4);
    fc_code code = fc_frame_validate(&frame, err);
    if (code == FC_OK)
        *view = frame;
    return code;
}

fc_code wire_get_frame_attributes(wire_reader *r, const fc_frame *frame, fc_error *err)
{
    /* Both layout checks proved the particles' bytes are in the payload, so count fits size_t. */
    size_t particles = (size_t)frame->count;
    if (frame->density)
        wire_get_f32_array(r, frame->density, particles, "density");
    if (frame->velocity)
        wire_get_f32_array(r, frame->velocity, 3 * particles, "velocity");
    if (frame->ids)
        wire_get_u32_array(r, frame->ids, particles, "ids");
    if (frame->radius)
        wire_get_f32_array(r, frame->radius, particles, "radius");
    wire_expect_end(r);
    return r->code != FC_OK ? r->code : fc_frame_validate(frame, err);
}

fc_code wire_frame_from_view(const fc_frame *view, fc_frame *out, fc_error *err)
{
    fc_frame frame;
    fc_code code = fc_frame_alloc(&frame, view->count, fc_frame_attributes(view), err);
    if (code != FC_OK)
        return code;
    size_t n = (size_t)view->count;
    memcpy(frame.positions, view->positions, 3 * n * sizeof(float));
    if (view->density)
        memcpy(frame.density, view->density, n * sizeof(float));
    if (view->velocity)
        memcpy(frame.velocity, view->velocity, 3 * n * sizeof(float));
    if (view->ids)
        memcpy(frame.ids, view->ids, n * sizeof(uint32_t));
    if (view->radius)
        memcpy(frame.radius, view->radius, n * sizeof(float));
    *out = frame;
    return FC_OK;
}
