/* reader_f32.c — raw little-endian float32 x y z triples, no header.
 *
 * On a little-endian host the file's bytes are the frame's positions: the
 * buffer the file was read into becomes the positions array when the caller
 * lets it (fc_cursor.adoptable), else one copy; then every value is checked
 * finite (what fc_field_store asks of a position; a finite float is always
 * in float range). Keeping the buffer saves a copy into fresh memory, 35-50 ms
 * on 1M particles on the 2-core VM (its page faults, not the copy, cost),
 * in the format fluidcast-bench writes its scenes in. A big-endian host
 * reads value by value. */
#include "reader_formats.h"

#include <math.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "reader_fields.h"

enum { F32_PARTICLE_BYTES = 12 };

static bool host_is_little_endian(void)
{
    const uint16_t probe = 1;
    uint8_t first;
    memcpy(&first, &probe, 1);
    return first == 1;
}

/* The first value that is not finite, as the value-by-value reader reports it. */
static fc_code check_finite(fc_cursor *c, const fc_frame *frame, fc_error *err)
{
    const float *values = frame->positions;
    uint64_t n = 3 * frame->count;
    for (uint64_t k = 0; k < n; k++)
        if (!isfinite(values[k])) {
            c->pos += (size_t)k * sizeof(float);
            return fc_field_reject(c, err, k / 3, (fc_field)(FC_FIELD_X + (int)(k % 3)), values[k]);
        }
    c->pos += (size_t)n * sizeof(float);
    return FC_OK;
}

static fc_code read_each(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    for (uint64_t i = 0; i < frame->count; i++) {
        for (fc_field axis = FC_FIELD_X; axis <= FC_FIELD_Z; axis++) {
            size_t value_offset = c->pos;
            double value = 0.0;
            if (!fc_cursor_read_scalar(c, FC_SCALAR_F32, false, &value))
                return fc_cursor_fail(c, err, "particle %llu: truncated", (unsigned long long)i);
            if (!fc_field_store(frame, i, axis, value)) {
                c->pos = value_offset;
                return fc_field_reject(c, err, i, axis, value);
            }
        }
    }
    return FC_OK;
}

fc_code fc_read_f32(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    c->binary = true;
    if (c->size % F32_PARTICLE_BYTES != 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: size %zu bytes is not a multiple of 12 (x y z float32)",
                            c->name, c->size);
    uint64_t count = c->size / F32_PARTICLE_BYTES;
    if (c->adoptable && c->pos == 0 && count > 0 && host_is_little_endian() &&
        (uintptr_t)c->adoptable % _Alignof(float) == 0) {
        frame->positions = (float *)(void *)c->adoptable;
        frame->count = count;
        c->adoptable = NULL;
        return check_finite(c, frame, err);
    }
    fc_code code = fc_reader_alloc_frame(c, frame, count, 0, err);
    if (code != FC_OK)
        return code;
    if (!host_is_little_endian() || fc_cursor_remaining(c) < count * F32_PARTICLE_BYTES)
        return read_each(c, frame, err);
    memcpy(frame->positions, c->data + c->pos, (size_t)count * F32_PARTICLE_BYTES);
    return check_finite(c, frame, err);
}
