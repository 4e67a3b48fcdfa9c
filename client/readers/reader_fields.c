/* reader_fields.c — field names, field sets and checked stores shared by the readers. */
#include "reader_fields.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include "fc_error.h"
#include "fc_frame.h"

static const struct {
    const char *name;
    fc_field field;
} field_names[] = {
    { "x", FC_FIELD_X },         { "y", FC_FIELD_Y },   { "z", FC_FIELD_Z },
    { "density", FC_FIELD_DENSITY }, { "rho", FC_FIELD_DENSITY },
    { "vx", FC_FIELD_VX },       { "vy", FC_FIELD_VY }, { "vz", FC_FIELD_VZ },
    { "id", FC_FIELD_ID },
    /* Houdini's point scale is the particle's radius (partio, SPlisHSPlasH's BGEO). */
    { "radius", FC_FIELD_RADIUS }, { "pscale", FC_FIELD_RADIUS },
};

fc_field fc_field_from_name(fc_span name)
{
    for (size_t i = 0; i < sizeof field_names / sizeof field_names[0]; i++) {
        if (fc_span_iequals(name, field_names[i].name))
            return field_names[i].field;
    }
    return FC_FIELD_NONE;
}

const char *fc_field_name(fc_field field)
{
    for (size_t i = 0; i < sizeof field_names / sizeof field_names[0]; i++) {
        if (field_names[i].field == field)
            return field_names[i].name;
    }
    return "(none)";
}

bool fc_field_set_add(fc_field_set *set, fc_field field)
{
    if (set->present[field])
        return false;
    set->present[field] = true;
    return true;
}

bool fc_field_set_attributes(const fc_field_set *set, uint32_t *attributes, const char **missing)
{
    if (!set->present[FC_FIELD_X] || !set->present[FC_FIELD_Y] || !set->present[FC_FIELD_Z]) {
        *missing = "x, y and z are required";
        return false;
    }
    int velocity_parts = set->present[FC_FIELD_VX] + set->present[FC_FIELD_VY] + set->present[FC_FIELD_VZ];
    if (velocity_parts != 0 && velocity_parts != 3) {
        *missing = "velocity needs all of vx, vy and vz";
        return false;
    }
    *attributes = (set->present[FC_FIELD_DENSITY] ? FC_ATTR_DENSITY : 0u) |
                  (velocity_parts == 3 ? FC_ATTR_VELOCITY : 0u) |
                  (set->present[FC_FIELD_ID] ? FC_ATTR_IDS : 0u) |
                  (set->present[FC_FIELD_RADIUS] ? FC_ATTR_RADIUS : 0u);
    return true;
}

fc_code fc_reader_alloc_frame(const fc_cursor *c, fc_frame *frame, uint64_t count,
                              uint32_t attributes, fc_error *err)
{
    if (count == 0)
        return fc_cursor_fail(c, err, "no particles");
    fc_error inner = { FC_OK, "" };
    fc_code code = fc_frame_alloc(frame, count, attributes, &inner);
    if (code != FC_OK)
        return fc_error_set(err, code, "%s: %llu particles: %s", c->name, (unsigned long long)count,
                            inner.message);
    return FC_OK;
}

static bool fits_float(double value)
{
    return isfinite(value) && value >= -FLT_MAX && value <= FLT_MAX;
}

static bool fits_id(double value)
{
    return value >= 0.0 && value <= (double)UINT32_MAX && (double)(uint32_t)value == value;
}

bool fc_field_store(fc_frame *frame, uint64_t index, fc_field field, double value)
{
    if (field == FC_FIELD_NONE)
        return true;
    if (field == FC_FIELD_ID) {
        if (!fits_id(value))
            return false;
        frame->ids[index] = (uint32_t)value;
        return true;
    }
    if (field == FC_FIELD_RADIUS) {
        /* Checked as stored: a radius too small for a float would be stored as 0. */
        float radius = (float)value;
        if (!(value > 0.0 && radius > 0.0f && radius <= FC_FRAME_MAX_RADIUS))
            return false;
        frame->radius[index] = radius;
        return true;
    }
    if (!fits_float(value))
        return false;
    switch (field) {
    case FC_FIELD_X:
    case FC_FIELD_Y:
    case FC_FIELD_Z:
        frame->positions[3 * index + (size_t)(field - FC_FIELD_X)] = (float)value;
        break;
    case FC_FIELD_VX:
    case FC_FIELD_VY:
    case FC_FIELD_VZ:
        frame->velocity[3 * index + (size_t)(field - FC_FIELD_VX)] = (float)value;
        break;
    case FC_FIELD_DENSITY:
        frame->density[index] = (float)value;
        break;
    default:
        break;
    }
    return true;
}

bool fc_field_store_position64(const fc_cursor *c, fc_frame *frame, uint64_t index, fc_field field, double value)
{
    fc_positions64 *p = c->positions64;
    if (p == NULL || field < FC_FIELD_X || field > FC_FIELD_Z)
        return fc_field_store(frame, index, field, value);
    if (!isfinite(value))
        return false;
    if (p->xyz == NULL) {
        p->count = frame->count;
        p->xyz = p->count <= SIZE_MAX / 3 / sizeof *p->xyz ? malloc((size_t)p->count * 3 * sizeof *p->xyz) : NULL;
        p->out_of_memory = p->xyz == NULL;
        if (p->xyz == NULL)
            return false;
    }
    if (index >= p->count)
        return false;
    p->xyz[3 * index + (uint64_t)(field - FC_FIELD_X)] = value;
    frame->positions[3 * index + (uint64_t)(field - FC_FIELD_X)] = 0.0f; /* set when the offset is known */
    return true;
}

const char *fc_field_requirement(fc_field field)
{
    return field == FC_FIELD_ID       ? "an integer in 0..4294967295"
           : field == FC_FIELD_RADIUS ? "a radius in (0, 1e6] (--radius R renders every particle at R)"
                                      : "a finite value in float range";
}

fc_code fc_field_reject(const fc_cursor *c, fc_error *err, uint64_t index, fc_field field, double value)
{
    const char *requirement = fc_field_requirement(field);
    return fc_cursor_fail(c, err, "particle %llu: %s = %g is not %s", (unsigned long long)index,
                          fc_field_name(field), value, requirement);
}
