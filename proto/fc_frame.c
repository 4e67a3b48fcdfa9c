/* fc_frame.c — allocating, validating and measuring particle frames. */
#include "fc_frame.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

/* NULL when count * values * bytes would not fit size_t: a size never wraps to a small block. */
static void *alloc_array(uint64_t count, size_t values_per_particle, size_t bytes_per_value)
{
    size_t particle_bytes = values_per_particle * bytes_per_value;
    if (count > SIZE_MAX / particle_bytes)
        return NULL;
    return malloc((size_t)count * particle_bytes);
}

fc_code fc_frame_alloc(fc_frame *frame, uint64_t count, uint32_t attributes, fc_error *err)
{
    memset(frame, 0, sizeof *frame);
    if (count == 0)
        return fc_error_set(err, FC_ERR_USAGE, "a frame needs at least one particle");
    if (attributes & ~(uint32_t)FC_ATTR_ALL)
        return fc_error_set(err, FC_ERR_USAGE, "unknown attribute bits 0x%x", attributes & ~(uint32_t)FC_ATTR_ALL);

    frame->count = count;
    frame->positions = alloc_array(count, 3, sizeof(float));
    bool ok = frame->positions != NULL;
    if (ok && (attributes & FC_ATTR_DENSITY))
        ok = (frame->density = alloc_array(count, 1, sizeof(float))) != NULL;
    if (ok && (attributes & FC_ATTR_VELOCITY))
        ok = (frame->velocity = alloc_array(count, 3, sizeof(float))) != NULL;
    if (ok && (attributes & FC_ATTR_IDS))
        ok = (frame->ids = alloc_array(count, 1, sizeof(uint32_t))) != NULL;
    if (ok && (attributes & FC_ATTR_RADIUS))
        ok = (frame->radius = alloc_array(count, 1, sizeof(float))) != NULL;
    if (!ok) {
        fc_frame_free(frame);
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate a frame of %llu particles",
                            (unsigned long long)count);
    }
    return FC_OK;
}

size_t fc_frame_particle_bytes(uint32_t attributes)
{
    size_t bytes = 3 * sizeof(float);
    if (attributes & FC_ATTR_DENSITY)
        bytes += sizeof(float);
    if (attributes & FC_ATTR_VELOCITY)
        bytes += 3 * sizeof(float);
    if (attributes & FC_ATTR_IDS)
        bytes += sizeof(uint32_t);
    if (attributes & FC_ATTR_RADIUS)
        bytes += sizeof(float);
    return bytes;
}

size_t fc_frame_block_size(uint64_t count, uint32_t attributes)
{
    size_t per_particle = fc_frame_particle_bytes(attributes);
    return count > SIZE_MAX / per_particle ? 0 : (size_t)count * per_particle;
}

void fc_frame_point_into_block(fc_frame *frame, uint8_t *block, uint64_t count, uint32_t attributes)
{
    size_t n = (size_t)count;
    memset(frame, 0, sizeof *frame);
    frame->count = count;
    frame->positions = (float *)block;
    block += 3 * n * sizeof(float);
    if (attributes & FC_ATTR_DENSITY) {
        frame->density = (float *)block;
        block += n * sizeof(float);
    }
    if (attributes & FC_ATTR_VELOCITY) {
        frame->velocity = (float *)block;
        block += 3 * n * sizeof(float);
    }
    if (attributes & FC_ATTR_IDS) {
        frame->ids = (uint32_t *)block;
        block += n * sizeof(uint32_t);
    }
    if (attributes & FC_ATTR_RADIUS)
        frame->radius = (float *)block;
}

void fc_frame_free(fc_frame *frame)
{
    free(frame->positions);
    free(frame->density);
    free(frame->velocity);
    free(frame->ids);
    free(frame->radius);
    memset(frame, 0, sizeof *frame);
}

uint32_t fc_frame_attributes(const fc_frame *frame)
{
    uint32_t attributes = 0;
    if (frame->density)
        attributes |= FC_ATTR_DENSITY;
    if (frame->velocity)
        attributes |= FC_ATTR_VELOCITY;
    if (frame->ids)
        attributes |= FC_ATTR_IDS;
    if (frame->radius)
        attributes |= FC_ATTR_RADIUS;
    return attributes;
}

/* Index of the first particle with a non-finite value among `per_particle`
 * interleaved floats, or `count` when all are finite. */
static uint64_t first_non_finite(const float *values, uint64_t count, size_t per_particle)
{
    for (uint64_t i = 0; i < count; i++)
        for (size_t k = 0; k < per_particle; k++)
            if (!isfinite(values[i * per_particle + k]))
                return i;
    return count;
}

/* Whether all n floats are finite: a NaN's or an infinity's exponent bits are
 * all ones. Branch-free, so the compiler vectorises the one pass over the
 * frame that the common, valid case needs. */
static bool all_finite(const float *values, size_t n)
{
    const uint32_t exponent = 0x7f800000u;
    uint32_t bad = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t bits;
        memcpy(&bits, values + i, sizeof bits);
        bad |= (bits & exponent) == exponent;
    }
    return bad == 0;
}

/* Whether every radius is in (0, FC_FRAME_MAX_RADIUS]; NaN fails both
 * comparisons. Branch-free like all_finite, for the same reason. */
static bool all_radii_valid(const float *radius, size_t n)
{
    uint32_t bad = 0;
    for (size_t i = 0; i < n; i++)
        bad |= !(radius[i] > 0.0f && radius[i] <= FC_FRAME_MAX_RADIUS);
    return bad == 0;
}

/* FC_ERR_INVALID_VALUE naming the first particle whose radius is not a usable splat size. */
static fc_code validate_radii(const fc_frame *frame, fc_error *err)
{
    if (frame->count <= SIZE_MAX && all_radii_valid(frame->radius, (size_t)frame->count))
        return FC_OK;
    for (uint64_t i = 0; i < frame->count; i++) {
        float r = frame->radius[i];
        if (!isfinite(r))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "particle %llu has a non-finite radius",
                                (unsigned long long)i);
        if (!(r > 0.0f && r <= FC_FRAME_MAX_RADIUS))
            return fc_error_set(err, FC_ERR_INVALID_VALUE,
                                "particle %llu has radius %g, outside (0, 1e6]",
                                (unsigned long long)i, (double)r);
    }
    return FC_OK;
}

fc_code fc_frame_validate(const fc_frame *frame, fc_error *err)
{
    const struct {
        const float *values;
        size_t per_particle;
        const char *what;
    } arrays[] = {
        {frame->positions, 3, "position"},
        {frame->density, 1, "density"},
        {frame->velocity, 3, "velocity"},
    };
    if (frame->count == 0 || !frame->positions)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "the frame has no particles");
    for (size_t a = 0; a < sizeof arrays / sizeof arrays[0]; a++) {
        if (!arrays[a].values)
            continue;
        if (frame->count <= SIZE_MAX / arrays[a].per_particle &&
            all_finite(arrays[a].values, (size_t)frame->count * arrays[a].per_particle))
            continue;
        uint64_t bad = first_non_finite(arrays[a].values, frame->count, arrays[a].per_particle);
        if (bad < frame->count)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "particle %llu has a non-finite %s",
                                (unsigned long long)bad, arrays[a].what);
    }
    return frame->radius ? validate_radii(frame, err) : FC_OK;
}

void fc_frame_bounds(const fc_frame *frame, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++)
        lo[k] = hi[k] = frame->positions[k];
    for (uint64_t i = 1; i < frame->count; i++) {
        const float *p = frame->positions + 3 * i;
        for (int k = 0; k < 3; k++) {
            lo[k] = p[k] < lo[k] ? p[k] : lo[k];
            hi[k] = p[k] > hi[k] ? p[k] : hi[k];
        }
    }
}
