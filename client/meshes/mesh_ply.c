/* mesh_ply.c — PLY with faces: the header's elements and properties, then
 * the data (ascii, binary_little_endian or binary_big_endian). The vertex
 * element gives x, y, z (any scalar type); the face element's list property
 * vertex_indices (or vertex_index, else its first list) gives polygons, fanned
 * into triangles. Other elements and properties are read past. */
#include "mesh_formats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

#define MAX_ELEMENTS 16
#define MAX_PROPERTIES 64
#define MAX_CORNERS 4096u
#define NONE (-1)

typedef struct ply_property {
    bool list;
    fc_scalar_type count_type;   /* list only */
    fc_scalar_type type;         /* the value's, or each item's */
    char name[32];
} ply_property;

typedef struct ply_element {
    char name[32];
    uint64_t count;
    ply_property properties[MAX_PROPERTIES];
    int property_count;
} ply_element;

typedef enum ply_encoding { PLY_ASCII, PLY_LITTLE, PLY_BIG } ply_encoding;

typedef struct ply_header {
    ply_encoding encoding;
    ply_element elements[MAX_ELEMENTS];
    int element_count;
} ply_header;

static bool scalar_type(fc_span s, fc_scalar_type *out)
{
    static const struct {
        const char *name;
        fc_scalar_type type;
    } table[] = {{"char", FC_SCALAR_I8},     {"int8", FC_SCALAR_I8},     {"uchar", FC_SCALAR_U8},
                 {"uint8", FC_SCALAR_U8},    {"short", FC_SCALAR_I16},   {"int16", FC_SCALAR_I16},
                 {"ushort", FC_SCALAR_U16},  {"uint16", FC_SCALAR_U16},  {"int", FC_SCALAR_I32},
                 {"int32", FC_SCALAR_I32},   {"uint", FC_SCALAR_U32},    {"uint32", FC_SCALAR_U32},
                 {"float", FC_SCALAR_F32},   {"float32", FC_SCALAR_F32}, {"double", FC_SCALAR_F64},
                 {"float64", FC_SCALAR_F64}};
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (fc_span_iequals(s, table[i].name)) {
            *out = table[i].type;
            return true;
        }
    return false;
}

static void copy_name(fc_span s, char out[32])
{
    size_t n = s.len < 31 ? s.len : 31;
    memcpy(out, s.ptr, n);
    out[n] = '\0';
}

static fc_code read_property(const fc_cursor *c, fc_span rest, ply_element *e, fc_error *err)
{
    if (e->property_count == MAX_PROPERTIES)
        return fc_cursor_fail(c, err, "more than %d properties in element %s", MAX_PROPERTIES, e->name);
    ply_property *p = &e->properties[e->property_count];
    fc_span a, b2, name;
    if (!fc_span_next_token(&rest, &a))
        return fc_cursor_fail(c, err, "a property without a type");
    p->list = fc_span_iequals(a, "list");
    bool ok = p->list ? fc_span_next_token(&rest, &a) && scalar_type(a, &p->count_type) &&
                            fc_span_next_token(&rest, &b2) && scalar_type(b2, &p->type)
                      : scalar_type(a, &p->type);
    if (!ok || !fc_span_next_token(&rest, &name))
        return fc_cursor_fail(c, err, "a property line that is not \"property TYPE NAME\" or \"property list "
                                      "COUNT_TYPE TYPE NAME\"");
    if (p->list && (p->count_type == FC_SCALAR_F32 || p->count_type == FC_SCALAR_F64))
        return fc_cursor_fail(c, err, "a list counted by a floating-point type");
    copy_name(name, p->name);
    e->property_count++;
    return FC_OK;
}

static fc_code read_format(const fc_cursor *c, fc_span rest, ply_header *h, fc_error *err)
{
    fc_span kind;
    if (!fc_span_next_token(&rest, &kind))
        return fc_cursor_fail(c, err, "a format line without its format");
    if (fc_span_iequals(kind, "ascii"))
        h->encoding = PLY_ASCII;
    else if (fc_span_iequals(kind, "binary_little_endian"))
        h->encoding = PLY_LITTLE;
    else if (fc_span_iequals(kind, "binary_big_endian"))
        h->encoding = PLY_BIG;
    else
        return fc_cursor_fail(c, err, "unknown PLY format (ascii, binary_little_endian or binary_big_endian)");
    return FC_OK;
}

static fc_code read_element(const fc_cursor *c, fc_span rest, ply_header *h, fc_error *err)
{
    if (h->element_count == MAX_ELEMENTS)
        return fc_cursor_fail(c, err, "more than %d elements", MAX_ELEMENTS);
    ply_element *e = &h->elements[h->element_count];
    fc_span name, count;
    if (!fc_span_next_token(&rest, &name) || !fc_span_next_token(&rest, &count) || !fc_span_to_count(count, &e->count))
        return fc_cursor_fail(c, err, "an element line that is not \"element NAME COUNT\"");
    copy_name(name, e->name);
    h->element_count++;
    return FC_OK;
}

static fc_code read_header(fc_cursor *c, ply_header *h, fc_error *err)
{
    fc_span line, keyword;
    if (!fc_cursor_next_line(c, &line) || !fc_span_iequals(fc_span_trim(line), "ply"))
        return fc_cursor_fail(c, err, "not a PLY file (the first line is not \"ply\")");
    bool has_format = false;
    while (fc_cursor_next_line(c, &line)) {
        fc_span rest = line;
        if (!fc_span_next_token(&rest, &keyword) || fc_span_iequals(keyword, "comment") ||
            fc_span_iequals(keyword, "obj_info"))
            continue;
        fc_code code = FC_OK;
        if (fc_span_iequals(keyword, "end_header"))
            return has_format ? FC_OK : fc_cursor_fail(c, err, "no format line in the header");
        if (fc_span_iequals(keyword, "format")) {
            code = read_format(c, rest, h, err);
            has_format = true;
        } else if (fc_span_iequals(keyword, "element")) {
            code = read_element(c, rest, h, err);
        } else if (fc_span_iequals(keyword, "property")) {
            code = h->element_count == 0 ? fc_cursor_fail(c, err, "a property before any element")
                                         : read_property(c, rest, &h->elements[h->element_count - 1], err);
        } else {
            code = fc_cursor_fail(c, err, "unknown header line");
        }
        if (code != FC_OK)
            return code;
    }
    return fc_cursor_fail(c, err, "the header has no end_header");
}

/* One value of the data: a token (ascii) or a scalar of `type`. */
static fc_code read_value(fc_cursor *c, const ply_header *h, fc_scalar_type type, double *out, fc_error *err)
{
    if (h->encoding == PLY_ASCII) {
        fc_span token;
        if (fc_cursor_next_token(c, &token) && fc_span_to_double(token, out))
            return FC_OK;
        return fc_cursor_fail(c, err, "the data ends early or holds something that is not a number");
    }
    if (fc_cursor_read_scalar(c, type, h->encoding == PLY_BIG, out))
        return FC_OK;
    return fc_cursor_fail(c, err, "the data ends inside an element");
}

static fc_code read_count(fc_cursor *c, const ply_header *h, const ply_property *p, uint64_t *count, fc_error *err)
{
    double v;
    fc_code code = read_value(c, h, p->count_type, &v, err);
    if (code != FC_OK)
        return code;
    if (!(v >= 0.0 && v <= (double)MAX_CORNERS) || v != floor(v))
        return fc_cursor_fail(c, err, "a list of %g items (a face has 3 to %u corners)", v, MAX_CORNERS);
    *count = (uint64_t)v;
    return FC_OK;
}

/* Indices of x, y, z in the vertex element, and of the face element's index list. */
static int property_named(const ply_element *e, const char *name)
{
    for (int i = 0; i < e->property_count; i++)
        if (strcmp(e->properties[i].name, name) == 0)
            return i;
    return NONE;
}

static int index_list(const ply_element *e)
{
    int named = property_named(e, "vertex_indices");
    if (named == NONE)
        named = property_named(e, "vertex_index");
    for (int i = 0; named == NONE && i < e->property_count; i++)
        if (e->properties[i].list)
            named = i;
    return named != NONE && e->properties[named].list ? named : NONE;
}

/* One item of element e: its vertex (xyz) or face (corners) as the roles say. */
static fc_code read_item(fc_cursor *c, const ply_header *h, const ply_element *e, const int xyz[3], int list,
                         fc_mesh_builder *b, uint64_t *corners, fc_error *err)
{
    double point[3] = {0, 0, 0};
    uint64_t corner_count = 0;
    for (int i = 0; i < e->property_count; i++) {
        const ply_property *p = &e->properties[i];
        double v;
        fc_code code;
        if (!p->list) {
            code = read_value(c, h, p->type, &v, err);
            for (int k = 0; k < 3 && code == FC_OK; k++)
                if (xyz[k] == i)
                    point[k] = v;
            if (code != FC_OK)
                return code;
            continue;
        }
        uint64_t n = 0;
        code = read_count(c, h, p, &n, err);
        for (uint64_t j = 0; j < n && code == FC_OK; j++) {
            code = read_value(c, h, p->type, &v, err);
            if (code == FC_OK && i == list) {
                if (!(v >= 0.0 && v < 4294967296.0) || v != floor(v))
                    return fc_cursor_fail(c, err, "a face corner %g is not a vertex index", v);
                corners[corner_count++] = (uint64_t)v;
            }
        }
        if (code != FC_OK)
            return code;
    }
    if (xyz[0] != NONE)
        return fc_mesh_builder_vertex(b, c, point, err);
    if (list != NONE)
        return fc_mesh_builder_polygon(b, c, corners, corner_count, err);
    return FC_OK;
}

static fc_code read_data(fc_cursor *c, const ply_header *h, fc_mesh_builder *b, uint64_t *corners, fc_error *err)
{
    c->binary = h->encoding != PLY_ASCII;
    for (int ei = 0; ei < h->element_count; ei++) {
        const ply_element *e = &h->elements[ei];
        bool vertex = strcmp(e->name, "vertex") == 0, face = strcmp(e->name, "face") == 0;
        int xyz[3] = {NONE, NONE, NONE};
        if (vertex) {
            xyz[0] = property_named(e, "x"), xyz[1] = property_named(e, "y"), xyz[2] = property_named(e, "z");
            if (xyz[0] == NONE || xyz[1] == NONE || xyz[2] == NONE)
                return fc_cursor_fail(c, err, "the vertex element lacks x, y or z");
        }
        int list = face ? index_list(e) : NONE;
        if (face && list == NONE)
            return fc_cursor_fail(c, err, "the face element has no vertex_indices list");
        fc_code code = fc_mesh_builder_reserve(b, c, vertex ? e->count : 0, face ? e->count : 0, err);
        if (e->property_count == 0)
            continue;   /* items of nothing: any count takes no data (and no time) */
        for (uint64_t i = 0; i < e->count && code == FC_OK; i++)
            code = read_item(c, h, e, xyz, list, b, corners, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

fc_code fc_read_mesh_ply(fc_cursor *c, fc_mesh_builder *b, fc_error *err)
{
    ply_header *h = calloc(1, sizeof *h);
    uint64_t *corners = malloc(MAX_CORNERS * sizeof *corners);
    fc_code code = h && corners ? read_header(c, h, err) : fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", c->name);
    if (code == FC_OK)
        code = read_data(c, h, b, corners, err);
    free(h);
    free(corners);
    return code;
}
