/* reader_f32.c — raw little-endian float32 x y z triples, no header. */
#include "reader_formats.h"

#include "fc_error.h"
#include "fc_frame.h"
#include "reader_fields.h"

enum { F32_PARTICLE_BYTES = 12 };

fc_code fc_read_f32(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    c->binary = true;
    if (c->size % F32_PARTICLE_BYTES != 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: size %zu bytes is not a multiple of 12 (x y z float32)",
                            c->name, c->size);
    uint64_t count = c->size / F32_PARTICLE_BYTES;
    fc_code code = fc_reader_alloc_frame(c, frame, count, 0, err);
    if (code != FC_OK)
        return code;
    for (uint64_t i = 0; i < count; i++) {
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
