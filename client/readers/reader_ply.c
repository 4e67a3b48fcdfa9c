/* reader_ply.c — PLY 1.0 (ascii, binary_little_endian, binary_big_endian).
 *
 * Particles come from the "vertex" element; every other element and property,
 * list properties included, is walked over so that elements before and after
 * the vertices are skipped at their exact size. */
#include "reader_formats.h"

#include <stdlib.h>
#include "fc_error.h"
#include "reader_fields.h"

enum { PLY_MAX_ELEMENTS = 16, PLY_MAX_PROPERTIES = 64 };

typedef enum ply_encoding { PLY_ASCII, PLY_BINARY_LE, PLY_BINARY_BE } ply_encoding;

typedef struct ply_property {
    fc_span name;
    bool is_list;
    fc_scalar_type count_type; /* lists only */
    fc_scalar_type type;       /* the value's type, or a list's item type */
    fc_field field;            /* what a vertex property provides */
} ply_property;

typedef struct ply_element {
    fc_span name;
    uint64_t count;
    size_t property_count;
    ply_property properties[PLY_MAX_PROPERTIES];
} ply_element;

typedef struct ply_header {
    bool have_format;
    ply_encoding encoding;
    size_t element_count;
    ply_element elements[PLY_MAX_ELEMENTS];
    const ply_element *vertex;
    fc_field_set fields;
} ply_header;

static const struct {
    const char *name;
    fc_scalar_type type;
} ply_type_names[] = {
    { "char", FC_SCALAR_I8 },    { "int8", FC_SCALAR_I8 },     { "uchar", FC_SCALAR_U8 },
    { "uint8", FC_SCALAR_U8 },   { "short", FC_SCALAR_I16 },   { "int16", FC_SCALAR_I16 },
    { "ushort", FC_SCALAR_U16 }, { "uint16", FC_SCALAR_U16 },  { "int", FC_SCALAR_I32 },
    { "int32", FC_SCALAR_I32 },  { "uint", FC_SCALAR_U32 },    { "uint32", FC_SCALAR_U32 },
    { "float", FC_SCALAR_F32 },  { "float32", FC_SCALAR_F32 }, { "double", FC_SCALAR_F64 },
    { "float64", FC_SCALAR_F64 },
};

/* ---- header ---- */

static fc_code ply_parse_type(const fc_cursor *c, fc_span token, fc_scalar_type *type, fc_error *err)
{
    for (size_t i = 0; i < sizeof ply_type_names / sizeof ply_type_names[0]; i++) {
        if (fc_span_iequals(token, ply_type_names[i].name)) {
            *type = ply_type_names[i].type;
            return FC_OK;
        }
    }
    char quoted[FC_QUOTE_MAX];
    return fc_cursor_fail(c, err, "unknown property type '%s'", fc_span_quote(token, quoted, sizeof quoted));
}

static fc_code ply_expect_line_end(const fc_cursor *c, fc_span rest, fc_error *err)
{
    fc_span extra;
    if (!fc_span_next_token(&rest, &extra))
        return FC_OK;
    char quoted[FC_QUOTE_MAX];
    return fc_cursor_fail(c, err, "unexpected '%s' in header line", fc_span_quote(extra, quoted, sizeof quoted));
}

static fc_code ply_parse_format(const fc_cursor *c, fc_span rest, ply_header *h, fc_error *err)
{
    fc_span encoding, version;
    double version_number = 0.0;
    if (h->have_format)
        return fc_cursor_fail(c, err, "second format line");
    if (!fc_span_next_token(&rest, &encoding) || !fc_span_next_token(&rest, &version))
        return fc_cursor_fail(c, err, "format line needs an encoding and a version");
    if (fc_span_iequals(encoding, "ascii"))
        h->encoding = PLY_ASCII;
    else if (fc_span_iequals(encoding, "binary_little_endian"))
        h->encoding = PLY_BINARY_LE;
    else if (fc_span_iequals(encoding, "binary_big_endian"))
        h->encoding = PLY_BINARY_BE;
    else {
        char quoted[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "unknown format '%s'", fc_span_quote(encoding, quoted, sizeof quoted));
    }
    if (!fc_span_to_double(version, &version_number) || version_number != 1.0) {
        char quoted[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "unsupported PLY version '%s' (only 1.0)",
                              fc_span_quote(version, quoted, sizeof quoted));
    }
    h->have_format = true;
    return ply_expect_line_end(c, rest, err);
}

static fc_code ply_parse_element(const fc_cursor *c, fc_span rest, ply_header *h, fc_error *err)
{
    fc_span name, count;
    if (h->element_count == PLY_MAX_ELEMENTS)
        return fc_cursor_fail(c, err, "more than %d elements", PLY_MAX_ELEMENTS);
    ply_element *e = &h->elements[h->element_count];
    if (!fc_span_next_token(&rest, &name) || !fc_span_next_token(&rest, &count))
        return fc_cursor_fail(c, err, "element line needs a name and a count");
    if (!fc_span_to_count(count, &e->count)) {
        char quoted[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "element count '%s' is not a non-negative integer",
                              fc_span_quote(count, quoted, sizeof quoted));
    }
    if (fc_span_iequals(name, "vertex")) {
        if (h->vertex != NULL)
            return fc_cursor_fail(c, err, "second vertex element");
        h->vertex = e;
    }
    e->name = name;
    h->element_count++;
    return ply_expect_line_end(c, rest, err);
}

/* Maps a vertex property to the particle field it provides. */
static fc_code ply_assign_field(const fc_cursor *c, ply_property *p, fc_field_set *fields, fc_error *err)
{
    char quoted[FC_QUOTE_MAX];
    p->field = fc_field_from_name(p->name);
    if (p->field == FC_FIELD_NONE)
        return FC_OK;
    if (p->is_list)
        return fc_cursor_fail(c, err, "vertex property '%s' is a list, expected a scalar",
                              fc_span_quote(p->name, quoted, sizeof quoted));
    if (!fc_field_set_add(fields, p->field))
        return fc_cursor_fail(c, err, "vertex property '%s' gives %s a second time",
                              fc_span_quote(p->name, quoted, sizeof quoted), fc_field_name(p->field));
    return FC_OK;
}

static fc_code ply_parse_property(const fc_cursor *c, fc_span rest, ply_header *h, fc_error *err)
{
    if (h->element_count == 0)
        return fc_cursor_fail(c, err, "property before any element");
    ply_element *e = &h->elements[h->element_count - 1];
    if (e->property_count == PLY_MAX_PROPERTIES)
        return fc_cursor_fail(c, err, "more than %d properties in one element", PLY_MAX_PROPERTIES);
    ply_property *p = &e->properties[e->property_count];
    fc_span type, count_type;
    if (!fc_span_next_token(&rest, &type))
        return fc_cursor_fail(c, err, "property line needs a type and a name");
    p->is_list = fc_span_iequals(type, "list");
    if (p->is_list) {
        if (!fc_span_next_token(&rest, &count_type) || !fc_span_next_token(&rest, &type))
            return fc_cursor_fail(c, err, "list property needs a count type and an item type");
        fc_code code = ply_parse_type(c, count_type, &p->count_type, err);
        if (code != FC_OK)
            return code;
    }
    fc_code code = ply_parse_type(c, type, &p->type, err);
    if (code != FC_OK)
        return code;
    if (!fc_span_next_token(&rest, &p->name))
        return fc_cursor_fail(c, err, "property line needs a name");
    e->property_count++;
    if (e == h->vertex) {
        code = ply_assign_field(c, p, &h->fields, err);
        if (code != FC_OK)
            return code;
    }
    return ply_expect_line_end(c, rest, err);
}

static fc_code ply_parse_header_line(const fc_cursor *c, fc_span line, ply_header *h, bool *done, fc_error *err)
{
    fc_span rest = line, keyword;
    if (!fc_span_next_token(&rest, &keyword))
        return FC_OK;
    if (fc_span_iequals(keyword, "end_header")) {
        *done = true;
        return ply_expect_line_end(c, rest, err);
    }
    if (fc_span_iequals(keyword, "comment") || fc_span_iequals(keyword, "obj_info"))
        return FC_OK;
    if (fc_span_iequals(keyword, "format"))
        return ply_parse_format(c, rest, h, err);
    if (fc_span_iequals(keyword, "element"))
        return ply_parse_element(c, rest, h, err);
    if (fc_span_iequals(keyword, "property"))
        return ply_parse_property(c, rest, h, err);
    char quoted[FC_QUOTE_MAX];
    return fc_cursor_fail(c, err, "unknown header keyword '%s'", fc_span_quote(keyword, quoted, sizeof quoted));
}

static fc_code ply_check_header(const fc_cursor *c, const ply_header *h, uint32_t *attributes, fc_error *err)
{
    const char *missing = NULL;
    if (!h->have_format)
        return fc_cursor_fail(c, err, "header has no format line");
    if (h->vertex == NULL)
        return fc_cursor_fail(c, err, "no vertex element");
    for (size_t i = 0; i < h->element_count; i++) {
        if (h->elements[i].property_count == 0) {
            char quoted[FC_QUOTE_MAX];
            return fc_cursor_fail(c, err, "element '%s' has no properties",
                                  fc_span_quote(h->elements[i].name, quoted, sizeof quoted));
        }
    }
    if (!fc_field_set_attributes(&h->fields, attributes, &missing))
        return fc_cursor_fail(c, err, "vertex properties: %s", missing);
    return FC_OK;
}

static fc_code ply_parse_header(fc_cursor *c, ply_header *h, uint32_t *attributes, fc_error *err)
{
    fc_span line;
    if (!fc_cursor_next_line(c, &line) || !fc_span_iequals(fc_span_trim(line), "ply"))
        return fc_cursor_fail(c, err, "not a PLY file (first line is not 'ply')");
    bool done = false;
    while (!done) {
        if (!fc_cursor_next_line(c, &line))
            return fc_cursor_fail(c, err, "header ends without end_header");
        fc_code code = ply_parse_header_line(c, line, h, &done, err);
        if (code != FC_OK)
            return code;
    }
    return ply_check_header(c, h, attributes, err);
}

/* Rejects element counts the remaining bytes cannot hold before anything is
 * allocated for them: every value takes at least one byte (ascii: a digit;
 * binary: its size; lists: their count). */
static fc_code ply_check_sizes(const fc_cursor *c, const ply_header *h, fc_error *err)
{
    uint64_t available = fc_cursor_remaining(c);
    for (size_t i = 0; i < h->element_count; i++) {
        const ply_element *e = &h->elements[i];
        uint64_t instance_bytes = 0;
        for (size_t j = 0; j < e->property_count; j++) {
            const ply_property *p = &e->properties[j];
            bool ascii = h->encoding == PLY_ASCII;
            instance_bytes += ascii ? 1 : fc_scalar_size(p->is_list ? p->count_type : p->type);
        }
        if (e->count > available / instance_bytes) {
            char quoted[FC_QUOTE_MAX];
            return fc_cursor_fail(c, err, "element '%s': %llu instances cannot fit in the %llu bytes after the header",
                                  fc_span_quote(e->name, quoted, sizeof quoted), (unsigned long long)e->count,
                                  (unsigned long long)fc_cursor_remaining(c));
        }
        available -= e->count * instance_bytes;
    }
    return FC_OK;
}

/* ---- binary body ---- */

static bool ply_valid_list_count(double count)
{
    return count >= 0.0 && count <= (double)UINT64_MAX / 2 && (double)(uint64_t)count == count;
}

static fc_code ply_binary_property(fc_cursor *c, const ply_property *p, bool big_endian, bool is_vertex,
                                   uint64_t index, fc_frame *frame, fc_error *err)
{
    char quoted[FC_QUOTE_MAX];
    size_t value_offset = c->pos;
    double value = 0.0;
    if (!fc_cursor_read_scalar(c, p->is_list ? p->count_type : p->type, big_endian, &value))
        return fc_cursor_fail(c, err, "instance %llu, property '%s': unexpected end of data",
                              (unsigned long long)index, fc_span_quote(p->name, quoted, sizeof quoted));
    if (p->is_list) {
        if (!ply_valid_list_count(value)) {
            c->pos = value_offset;
            return fc_cursor_fail(c, err, "instance %llu, list '%s': count %g is not a valid length",
                                  (unsigned long long)index, fc_span_quote(p->name, quoted, sizeof quoted), value);
        }
        if (!fc_cursor_skip_items(c, (uint64_t)value, fc_scalar_size(p->type)))
            return fc_cursor_fail(c, err, "instance %llu, list '%s': %g items run past the end of the data",
                                  (unsigned long long)index, fc_span_quote(p->name, quoted, sizeof quoted), value);
        return FC_OK;
    }
    if (is_vertex && !fc_field_store(frame, index, p->field, value)) {
        c->pos = value_offset;
        return fc_field_reject(c, err, index, p->field, value);
    }
    return FC_OK;
}

static fc_code ply_read_binary(fc_cursor *c, const ply_header *h, fc_frame *frame, fc_error *err)
{
    bool big_endian = h->encoding == PLY_BINARY_BE;
    c->binary = true;
    for (size_t i = 0; i < h->element_count; i++) {
        const ply_element *e = &h->elements[i];
        bool is_vertex = e == h->vertex;
        for (uint64_t index = 0; index < e->count; index++) {
            for (size_t j = 0; j < e->property_count; j++) {
                fc_code code = ply_binary_property(c, &e->properties[j], big_endian, is_vertex, index, frame, err);
                if (code != FC_OK)
                    return code;
            }
        }
    }
    if (fc_cursor_remaining(c) != 0)
        return fc_cursor_fail(c, err, "%zu bytes after the last element", fc_cursor_remaining(c));
    return FC_OK;
}

/* ---- ascii body: one instance per line ---- */

/* Values still needed from property `from` on, counting each list as its count alone. */
static size_t ply_min_values(const ply_element *e, size_t from)
{
    return e->property_count - from;
}

typedef struct ply_ascii_line {
    fc_span rest;       /* tokens not yet consumed */
    size_t consumed;
    size_t found;       /* tokens on the whole line */
} ply_ascii_line;

static fc_code ply_ascii_short(const fc_cursor *c, const ply_ascii_line *l, size_t still_needed, fc_error *err)
{
    return fc_cursor_fail(c, err, "expected %zu values, found %zu", l->consumed + still_needed, l->found);
}

static fc_code ply_ascii_list(const fc_cursor *c, ply_ascii_line *l, const ply_element *e, size_t j, fc_error *err)
{
    fc_span token;
    double count = 0.0;
    if (!fc_span_next_token(&l->rest, &token))
        return ply_ascii_short(c, l, ply_min_values(e, j), err);
    l->consumed++;
    if (!fc_span_to_double(token, &count) || !ply_valid_list_count(count)) {
        char quoted_name[FC_QUOTE_MAX], quoted_count[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "list '%s': count '%s' is not a valid length",
                              fc_span_quote(e->properties[j].name, quoted_name, sizeof quoted_name),
                              fc_span_quote(token, quoted_count, sizeof quoted_count));
    }
    for (uint64_t k = 0; k < (uint64_t)count; k++) {
        if (!fc_span_next_token(&l->rest, &token))
            return ply_ascii_short(c, l, (size_t)((uint64_t)count - k) + ply_min_values(e, j + 1), err);
        l->consumed++;
    }
    return FC_OK;
}

static fc_code ply_ascii_scalar(const fc_cursor *c, ply_ascii_line *l, const ply_element *e, size_t j,
                                bool is_vertex, uint64_t index, fc_frame *frame, fc_error *err)
{
    const ply_property *p = &e->properties[j];
    fc_span token;
    double value = 0.0;
    if (!fc_span_next_token(&l->rest, &token))
        return ply_ascii_short(c, l, ply_min_values(e, j), err);
    l->consumed++;
    if (!is_vertex || p->field == FC_FIELD_NONE)
        return FC_OK;
    if (!fc_span_to_double(token, &value)) {
        char quoted[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "particle %llu: %s: '%s' is not a number", (unsigned long long)index,
                              fc_field_name(p->field), fc_span_quote(token, quoted, sizeof quoted));
    }
    if (!fc_field_store(frame, index, p->field, value))
        return fc_field_reject(c, err, index, p->field, value);
    return FC_OK;
}

static fc_code ply_ascii_instance(const fc_cursor *c, fc_span line, const ply_element *e, bool is_vertex,
                                  uint64_t index, fc_frame *frame, fc_error *err)
{
    ply_ascii_line l = { line, 0, fc_span_count_tokens(line) };
    for (size_t j = 0; j < e->property_count; j++) {
        fc_code code = e->properties[j].is_list ? ply_ascii_list(c, &l, e, j, err)
                                                : ply_ascii_scalar(c, &l, e, j, is_vertex, index, frame, err);
        if (code != FC_OK)
            return code;
    }
    if (l.consumed != l.found)
        return fc_cursor_fail(c, err, "expected %zu values, found %zu", l.consumed, l.found);
    return FC_OK;
}

static fc_code ply_read_ascii(fc_cursor *c, const ply_header *h, fc_frame *frame, fc_error *err)
{
    fc_span line;
    for (size_t i = 0; i < h->element_count; i++) {
        const ply_element *e = &h->elements[i];
        for (uint64_t index = 0; index < e->count; index++) {
            if (!fc_cursor_next_nonblank_line(c, &line)) {
                char quoted[FC_QUOTE_MAX];
                return fc_cursor_fail(c, err, "data ends after %llu of %llu '%s' lines", (unsigned long long)index,
                                      (unsigned long long)e->count, fc_span_quote(e->name, quoted, sizeof quoted));
            }
            fc_code code = ply_ascii_instance(c, line, e, e == h->vertex, index, frame, err);
            if (code != FC_OK)
                return code;
        }
    }
    if (fc_cursor_next_nonblank_line(c, &line))
        return fc_cursor_fail(c, err, "unexpected data after the last element");
    return FC_OK;
}

fc_code fc_read_ply(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    /* The header holds PLY_MAX_ELEMENTS x PLY_MAX_PROPERTIES entries: too big for the stack. */
    ply_header *h = calloc(1, sizeof *h);
    if (h == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory for the PLY header", c->name);
    uint32_t attributes = 0;
    fc_code code = ply_parse_header(c, h, &attributes, err);
    if (code == FC_OK)
        code = ply_check_sizes(c, h, err);
    if (code == FC_OK)
        code = fc_reader_alloc_frame(c, frame, h->vertex->count, attributes, err);
    if (code == FC_OK)
        code = h->encoding == PLY_ASCII ? ply_read_ascii(c, h, frame, err) : ply_read_binary(c, h, frame, err);
    free(h);
    return code;
}
