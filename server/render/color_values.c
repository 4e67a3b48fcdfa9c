/* color_values.c — the colouring attribute per particle, on the GPU. */
#include "color_values.h"

#include <math.h>
#include <stdlib.h>

#include "fc_error.h"
#include "gl_util.h"

fc_color_values fc_color_values_init(void)
{
    return (fc_color_values){0};
}

void fc_color_values_release(fc_color_values *v)
{
    glDeleteBuffers(1, &v->buffer);
    free(v->staging);
    *v = fc_color_values_init();
}

/* The attribute's array in the frame, NULL when the frame has none. */
static const float *attribute_of(const fc_frame *frame, fc_color_by by)
{
    return by == FC_COLOR_BY_SPEED ? frame->velocity : by == FC_COLOR_BY_DENSITY ? frame->density : NULL;
}

static const char *attribute_name(fc_color_by by)
{
    return by == FC_COLOR_BY_SPEED ? "speed" : "density";
}

static const char *missing_arrays(fc_color_by by)
{
    return by == FC_COLOR_BY_SPEED ? "velocities" : "densities";
}

static fc_code reserve_staging(fc_color_values *v, uint64_t count, fc_error *err)
{
    if (count <= v->staging_capacity)
        return FC_OK;
    float *grown = realloc(v->staging, count * sizeof *grown);
    if (!grown)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for %llu colour values", (unsigned long long)count);
    v->staging = grown;
    v->staging_capacity = count;
    return FC_OK;
}

/* The buffer grows to hold `count` floats; a new one replaces it, since the
 * old values are rewritten anyway. */
static fc_code reserve_buffer(fc_color_values *v, uint64_t count, fc_error *err)
{
    if (v->buffer && count <= v->capacity)
        return FC_OK;
    glDeleteBuffers(1, &v->buffer);
    glCreateBuffers(1, &v->buffer);
    /* One float at least: a zero-sized buffer cannot be bound. */
    uint64_t floats = count > 0 ? count : 1;
    glNamedBufferStorage(v->buffer, (GLsizeiptr)(floats * sizeof(float)), NULL, GL_DYNAMIC_STORAGE_BIT);
    v->capacity = floats;
    v->allocations++;
    return fc_gl_check("allocating the colour values", err);
}

static void gather(float *out, const fc_frame *frame, const uint32_t *order, fc_color_by by)
{
    const float *source = attribute_of(frame, by);
    for (uint64_t slot = 0; slot < frame->count; slot++) {
        uint64_t i = order ? order[slot] : slot;
        if (by == FC_COLOR_BY_SPEED) {
            const float *u = source + 3 * i;
            out[slot] = sqrtf(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        } else {
            out[slot] = source[i];
        }
    }
}

fc_code fc_color_values_update(fc_color_values *v, const fc_frame *frame, const uint32_t *order, fc_color_by by,
                               uint64_t upload, fc_error *err)
{
    if (!attribute_of(frame, by) && frame->count > 0)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "color_by %s: the frame has no %s", attribute_name(by),
                            missing_arrays(by));
    if (v->buffer && v->filled_upload == upload && v->filled_order == order && v->filled_by == by)
        return FC_OK;
    v->filled_upload = 0;
    fc_code code = reserve_staging(v, frame->count, err);
    if (code == FC_OK)
        code = reserve_buffer(v, frame->count, err);
    if (code != FC_OK)
        return code;
    gather(v->staging, frame, order, by);
    /* The driver orders the copy after the draws still reading the old values. */
    if (frame->count > 0)
        glNamedBufferSubData(v->buffer, 0, (GLsizeiptr)(frame->count * sizeof(float)), v->staging);
    code = fc_gl_check("uploading the colour values", err);
    if (code == FC_OK) {
        v->filled_upload = upload;
        v->filled_order = order;
        v->filled_by = by;
    }
    return code;
}

void fc_color_values_bind(const fc_color_values *v)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FC_COLOR_VALUES_BINDING, v->buffer);
}

void fc_color_values_tally(const fc_color_values *v, fc_gpu_memory *m)
{
    if (v->buffer)
        m->particle_bytes += v->capacity * sizeof(float);
    m->allocations += v->allocations;
}
