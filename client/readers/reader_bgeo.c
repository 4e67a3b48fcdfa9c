/* reader_bgeo.c — Houdini's classic binary geometry (.bgeo, format V5) as partio
 * writes it, which is SPlisHSPlasH's default particle output.
 *
 * Layout (every number big-endian): "Bgeo" 'V', int32 version (5), then int32
 * nPoints nPrims nPointGroups nPrimGroups nPointAttrib nVertexAttrib nPrimAttrib
 * nAttrib; nPointAttrib definitions (uint16 name length, name, uint16 components,
 * int32 type: 0 float, 1 int, 5 vector with one default per component, 4 index
 * with an int32 count of uint16-length strings); then per point float32 x y z w
 * followed by each attribute's components as 4-byte values. Vertex, primitive and
 * detail sections follow the points in this format and are not read.
 *
 * partio gzips its output while keeping the .bgeo name, so gzip is recognised by
 * its magic bytes, never by the name. */
#include "reader_formats.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "reader_fields.h"
#include "reader_inflate.h"

enum {
    BGEO_VERSION = 5,
    BGEO_MAX_ATTRIBUTES = 256,
    BGEO_POSITION_BYTES = 16, /* x y z w */
    BGEO_TYPE_FLOAT = 0,
    BGEO_TYPE_INT = 1,
    BGEO_TYPE_INDEX = 4,
    BGEO_TYPE_VECTOR = 5
};

#define BGEO_HOW_TO_EXPORT                                                                               \
    "export classic BGEO instead: save as .bhclassic in Houdini (or convert: gconvert in.bgeo.sc "      \
    "out.bhclassic), or write .bgeo with partio (SPlisHSPlasH's default)"

typedef struct bgeo_attribute {
    fc_span name;
    uint16_t components;
    int32_t type;
    fc_field first; /* the field of component 0, FC_FIELD_NONE when not read */
} bgeo_attribute;

typedef struct bgeo_header {
    uint64_t points;
    size_t attribute_count;
    bgeo_attribute attributes[BGEO_MAX_ATTRIBUTES];
    size_t point_bytes; /* x y z w and every attribute */
    fc_field_set fields;
} bgeo_header;

static bool starts_with(const fc_cursor *c, const char *magic, size_t len)
{
    return c->size >= len && memcmp(c->data, magic, len) == 0;
}

static bool ends_with(const char *name, const char *suffix)
{
    size_t n = strlen(name), m = strlen(suffix);
    return n >= m && fc_span_iequals((fc_span){ name + n - m, m }, suffix);
}

/* The geometry files that are not classic BGEO, each refused with what to do instead. */
static fc_code bgeo_refuse_other(const fc_cursor *c, fc_error *err)
{
    if (starts_with(c, "\x7fNSJ", 4))
        return fc_error_set(err, FC_ERR_PARSE, "%s: binary JSON BGEO (Houdini 12 and later) is not supported; %s",
                            c->name, BGEO_HOW_TO_EXPORT);
    if (ends_with(c->name, ".sc"))
        return fc_error_set(err, FC_ERR_PARSE, "%s: blosc-compressed BGEO (.bgeo.sc) is not supported; %s", c->name,
                            BGEO_HOW_TO_EXPORT);
    if (starts_with(c, "[", 1) || starts_with(c, "{", 1) || starts_with(c, "PGEOMETRY", 9))
        return fc_error_set(err, FC_ERR_PARSE, "%s: ASCII Houdini geometry is not supported; %s", c->name,
                            BGEO_HOW_TO_EXPORT);
    return fc_error_set(err, FC_ERR_PARSE, "%s: not a classic BGEO file (no 'BgeoV' magic); %s", c->name,
                        BGEO_HOW_TO_EXPORT);
}

static bool read_i32(fc_cursor *c, int32_t *out)
{
    double value;
    if (!fc_cursor_read_scalar(c, FC_SCALAR_I32, true, &value))
        return false;
    *out = (int32_t)value;
    return true;
}

static bool read_u16(fc_cursor *c, uint16_t *out)
{
    double value;
    if (!fc_cursor_read_scalar(c, FC_SCALAR_U16, true, &value))
        return false;
    *out = (uint16_t)value;
    return true;
}

/* A uint16-length string (attribute names, index values). */
static bool read_string(fc_cursor *c, fc_span *out)
{
    uint16_t len;
    size_t start = c->pos;
    if (!read_u16(c, &len) || fc_cursor_remaining(c) < len) {
        c->pos = start;
        return false;
    }
    out->ptr = (const char *)c->data + c->pos;
    out->len = len;
    c->pos += len;
    return true;
}

static fc_code bgeo_parse_counts(fc_cursor *c, bgeo_header *h, int32_t *attribute_count, fc_error *err)
{
    static const char *const names[] = { "version", "nPoints", "nPrims", "nPointGroups", "nPrimGroups",
                                         "nPointAttrib", "nVertexAttrib", "nPrimAttrib", "nAttrib" };
    int32_t values[9];
    c->pos = 5; /* after "BgeoV" */
    for (size_t i = 0; i < 9; i++) {
        if (!read_i32(c, &values[i]))
            return fc_cursor_fail(c, err, "header ends before %s", names[i]);
        if (values[i] < 0)
            return fc_cursor_fail(c, err, "%s is negative (%d)", names[i], (int)values[i]);
    }
    if (values[0] != BGEO_VERSION)
        return fc_error_set(err, FC_ERR_PARSE, "%s: classic BGEO version %d is not supported (only %d, as partio writes)",
                            c->name, (int)values[0], BGEO_VERSION);
    h->points = (uint64_t)values[1];
    *attribute_count = values[5];
    if (values[5] > BGEO_MAX_ATTRIBUTES)
        return fc_cursor_fail(c, err, "%d point attributes (at most %d)", (int)values[5], BGEO_MAX_ATTRIBUTES);
    return FC_OK;
}

/* The frame field an attribute's name and shape give; FC_FIELD_NONE to skip it. */
static fc_code bgeo_assign_field(const fc_cursor *c, bgeo_attribute *a, fc_field_set *fields, fc_error *err)
{
    static const char *const velocity_names[] = { "v", "vel", "velocity" };
    static const char *const density_names[] = { "density", "rho", "dens" };
    static const char *const id_names[] = { "id", "ids", "pid" };
    char quoted[FC_QUOTE_MAX];
    size_t wanted = 1;
    a->first = FC_FIELD_NONE;
    for (size_t i = 0; i < 3; i++) {
        if (fc_span_iequals(a->name, velocity_names[i]))
            a->first = FC_FIELD_VX, wanted = 3;
        else if (fc_span_iequals(a->name, density_names[i]))
            a->first = FC_FIELD_DENSITY;
        else if (fc_span_iequals(a->name, id_names[i]))
            a->first = FC_FIELD_ID;
    }
    /* Houdini's point scale is the particle's radius (partio writes it as pscale). */
    if (fc_span_iequals(a->name, "pscale") || fc_span_iequals(a->name, "radius"))
        a->first = FC_FIELD_RADIUS;
    if (a->first == FC_FIELD_NONE)
        return FC_OK;
    if (a->type == BGEO_TYPE_INDEX || a->components != wanted)
        return fc_cursor_fail(c, err, "point attribute '%s' has %u %s components, %s needs %zu numbers",
                              fc_span_quote(a->name, quoted, sizeof quoted), (unsigned)a->components,
                              a->type == BGEO_TYPE_INDEX ? "string-index" : "numeric", fc_field_name(a->first),
                              wanted);
    for (size_t k = 0; k < wanted; k++) {
        if (!fc_field_set_add(fields, (fc_field)(a->first + k)))
            return fc_cursor_fail(c, err, "point attribute '%s' gives %s a second time",
                                  fc_span_quote(a->name, quoted, sizeof quoted), fc_field_name(a->first));
    }
    return FC_OK;
}

/* One point attribute's definition: name, components, type and its defaults or index strings. */
static fc_code bgeo_parse_attribute(fc_cursor *c, bgeo_attribute *a, fc_field_set *fields, fc_error *err)
{
    char quoted[FC_QUOTE_MAX];
    if (!read_string(c, &a->name))
        return fc_cursor_fail(c, err, "point attribute name runs past the end of the data");
    if (!read_u16(c, &a->components) || !read_i32(c, &a->type))
        return fc_cursor_fail(c, err, "point attribute '%s': definition is truncated",
                              fc_span_quote(a->name, quoted, sizeof quoted));
    if (a->type == BGEO_TYPE_INDEX) {
        int32_t strings;
        if (!read_i32(c, &strings) || strings < 0)
            return fc_cursor_fail(c, err, "point attribute '%s': bad or missing index string count",
                                  fc_span_quote(a->name, quoted, sizeof quoted));
        for (int32_t i = 0; i < strings; i++) {
            fc_span value;
            if (!read_string(c, &value))
                return fc_cursor_fail(c, err, "point attribute '%s': index string %d runs past the end of the data",
                                      fc_span_quote(a->name, quoted, sizeof quoted), (int)i);
        }
    } else if (a->type == BGEO_TYPE_FLOAT || a->type == BGEO_TYPE_INT || a->type == BGEO_TYPE_VECTOR) {
        if (!fc_cursor_skip_items(c, a->components, 4))
            return fc_cursor_fail(c, err, "point attribute '%s': defaults run past the end of the data",
                                  fc_span_quote(a->name, quoted, sizeof quoted));
    } else {
        return fc_cursor_fail(c, err, "point attribute '%s': unsupported type %d (float 0, int 1, index 4, vector 5)",
                              fc_span_quote(a->name, quoted, sizeof quoted), (int)a->type);
    }
    if (a->components == 0)
        return fc_cursor_fail(c, err, "point attribute '%s' has no components",
                              fc_span_quote(a->name, quoted, sizeof quoted));
    return bgeo_assign_field(c, a, fields, err);
}

static fc_code bgeo_parse_header(fc_cursor *c, bgeo_header *h, fc_error *err)
{
    int32_t attribute_count = 0;
    fc_code code = bgeo_parse_counts(c, h, &attribute_count, err);
    if (code != FC_OK)
        return code;
    h->fields.present[FC_FIELD_X] = h->fields.present[FC_FIELD_Y] = h->fields.present[FC_FIELD_Z] = true;
    h->point_bytes = BGEO_POSITION_BYTES;
    for (int32_t i = 0; i < attribute_count; i++) {
        bgeo_attribute *a = &h->attributes[h->attribute_count++];
        code = bgeo_parse_attribute(c, a, &h->fields, err);
        if (code != FC_OK)
            return code;
        h->point_bytes += (size_t)a->components * 4;
    }
    if (h->points > fc_cursor_remaining(c) / h->point_bytes)
        return fc_cursor_fail(c, err, "%llu points of %zu bytes cannot fit in the %zu bytes left",
                              (unsigned long long)h->points, h->point_bytes, fc_cursor_remaining(c));
    return FC_OK;
}

/* Reads one 4-byte value: int32 for int and index attributes, float32 otherwise. */
static double bgeo_read_value(fc_cursor *c, int32_t type)
{
    double value = 0.0;
    bool is_int = type == BGEO_TYPE_INT || type == BGEO_TYPE_INDEX;
    fc_cursor_read_scalar(c, is_int ? FC_SCALAR_I32 : FC_SCALAR_F32, true, &value); /* the header checked the size */
    return value;
}

static fc_code bgeo_store(fc_cursor *c, fc_frame *frame, uint64_t i, fc_field field, double value, fc_error *err)
{
    if (fc_field_store(frame, i, field, value))
        return FC_OK;
    c->pos -= 4;
    return fc_field_reject(c, err, i, field, value);
}

static fc_code bgeo_read_points(fc_cursor *c, const bgeo_header *h, fc_frame *frame, fc_error *err)
{
    for (uint64_t i = 0; i < h->points; i++) {
        for (fc_field axis = FC_FIELD_X; axis <= FC_FIELD_Z; axis++) {
            fc_code code = bgeo_store(c, frame, i, axis, bgeo_read_value(c, BGEO_TYPE_FLOAT), err);
            if (code != FC_OK)
                return code;
        }
        c->pos += 4; /* w: Houdini's homogeneous weight, 1 for particles */
        for (size_t a = 0; a < h->attribute_count; a++) {
            const bgeo_attribute *attr = &h->attributes[a];
            if (attr->first == FC_FIELD_NONE) {
                c->pos += (size_t)attr->components * 4;
                continue;
            }
            for (uint16_t k = 0; k < attr->components; k++) {
                fc_code code = bgeo_store(c, frame, i, (fc_field)(attr->first + k), bgeo_read_value(c, attr->type), err);
                if (code != FC_OK)
                    return code;
            }
        }
    }
    return FC_OK;
}

static fc_code bgeo_read_classic(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    c->binary = true;
    if (!starts_with(c, "BgeoV", 5))
        return bgeo_refuse_other(c, err);
    bgeo_header *h = calloc(1, sizeof *h);
    if (h == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: cannot allocate the BGEO header", c->name);
    fc_code code = bgeo_parse_header(c, h, err);
    uint32_t attributes = 0;
    const char *missing = NULL;
    if (code == FC_OK && !fc_field_set_attributes(&h->fields, &attributes, &missing))
        code = fc_cursor_fail(c, err, "%s", missing);
    if (code == FC_OK)
        code = fc_reader_alloc_frame(c, frame, h->points, attributes, err);
    if (code == FC_OK)
        code = bgeo_read_points(c, h, frame, err);
    free(h);
    return code;
}

/* Byte offsets in a gzip'd file's messages count the inflated data: say so after the name. */
static void note_inflated(const char *name, fc_error *err)
{
    size_t prefix = strlen(name) + 2; /* "name: " */
    if (strncmp(err->message, name, prefix - 2) != 0 || strncmp(err->message + prefix - 2, ": ", 2) != 0)
        return;
    char rest[FC_ERROR_MESSAGE_MAX];
    snprintf(rest, sizeof rest, "%s", err->message + prefix);
    fc_error_set(err, FC_ERR_PARSE, "%s: gzip'd BGEO, after inflating: %s", name, rest);
}

fc_code fc_read_bgeo(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    if (!fc_is_gzip(c->data, c->size))
        return bgeo_read_classic(c, frame, err);
    uint8_t *plain = NULL;
    size_t plain_size = 0;
    fc_code code = fc_inflate(c->name, "gzip", c->data, c->size, true, 0, &plain, &plain_size, err);
    if (code != FC_OK)
        return code;
    fc_cursor inner;
    fc_cursor_init(&inner, plain, plain_size, c->name);
    inner.options = c->options;
    inner.extras = c->extras;
    inner.positions64 = c->positions64;
    code = plain_size == 0 ? fc_error_set(err, FC_ERR_PARSE, "%s: gzip holds no data", c->name)
                           : bgeo_read_classic(&inner, frame, err);
    free(plain);
    if (code == FC_ERR_PARSE && err != NULL)
        note_inflated(c->name, err);
    return code;
}
