/* reader_vtkxml.c — VTK XML UnstructuredGrid (.vtu) and PolyData (.vtp) files,
 * as ParaView, GPUSPH, PySPH and VTK's own writers produce them.
 *
 * The XML is parsed with expat. The particles are the Piece's Points; point
 * data arrays named like velocity, density or an id fill the frame's other
 * fields. DataArrays are "ascii" text, inline "binary" (base64) or "appended"
 * at an offset into the AppendedData section, which is base64 or raw bytes.
 * Raw appended bytes make the file invalid XML, so expat sees the file only up
 * to the AppendedData start tag, and the arrays are read from the bytes after
 * its '_' by offset (reader_vtkxml_xml.c, shared with the .vtp mesh reader).
 * Binary data carries VTK's header (UInt32 or UInt64 words, in the file's byte
 * order) and may be in vtkZLibDataCompressor blocks (reader_vtkxml_data.c).
 * Cells and other arrays are not read. */
#include "reader_formats.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "reader_fields.h"
#include "reader_vtkxml_data.h"
#include "reader_vtkxml_xml.h"

/* VX_ARRAYS: one array per field group (positions, velocity, density, ids, radius). */
enum { VX_MAX_DEPTH = 64, VX_ARRAYS = 5, VX_NAME_MAX = 64 };

typedef enum vx_element {
    VX_OTHER,
    VX_FILE,
    VX_DATASET,
    VX_PIECE,
    VX_POINTS,
    VX_POINT_DATA,
    VX_DATA_ARRAY,
    VX_APPENDED
} vx_element;

typedef enum vx_format { VX_ASCII, VX_BINARY, VX_APPENDED_FORMAT } vx_format;

typedef struct vx_array {
    fc_field first; /* FC_FIELD_X (the points), VX, DENSITY or ID */
    char name[VX_NAME_MAX];
    fc_scalar_type type;
    uint64_t components;
    vx_format format;
    uint64_t offset;  /* appended arrays */
    char *text;       /* inline arrays: the element's own text */
    size_t text_len, text_cap;
    size_t line;      /* where the DataArray starts, for messages */
} vx_array;

typedef struct vx_doc {
    fc_vx_xml xml; /* the file, its first error, its encoding */
    size_t depth;
    vx_element stack[VX_MAX_DEPTH];
    size_t pieces;
    uint64_t points;
    vx_array arrays[VX_ARRAYS];
    size_t array_count;
    vx_array *collecting; /* the inline DataArray whose text is being gathered */
    fc_field_set fields;
} vx_doc;

static bool parse_count(const char *text, uint64_t *out)
{
    return text != NULL && fc_span_to_count(fc_span_trim((fc_span){ text, strlen(text) }), out);
}

/* ---- elements ---- */

static void on_file(vx_doc *d, const XML_Char **attrs)
{
    const char *type = fc_vx_attribute(attrs, "type");
    if (type == NULL || (strcmp(type, "UnstructuredGrid") != 0 && strcmp(type, "PolyData") != 0)) {
        if (type != NULL && strcmp(type, "Collection") == 0)
            return fc_vx_fail(&d->xml, FC_ERR_PARSE,
                              "a .pvd collection, not a dataset: name it .pvd, or give one of its files");
        return fc_vx_fail(&d->xml, FC_ERR_PARSE,
                          "VTKFile type '%.40s' is not a particle dataset (UnstructuredGrid .vtu or "
                                        "PolyData .vtp)", type ? type : "(none)");
    }
    fc_vx_on_file(&d->xml, attrs);
}

static void on_piece(vx_doc *d, const XML_Char **attrs)
{
    if (++d->pieces > 1)
        return fc_vx_fail(&d->xml, FC_ERR_PARSE,
                          "a second Piece: only single-piece files are read (merge the pieces or give "
                                        "the piece files one by one)");
    if (!parse_count(fc_vx_attribute(attrs, "NumberOfPoints"), &d->points))
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "Piece lacks a non-negative integer NumberOfPoints");
}

/* The field a point data array's name gives (case-insensitive), with the component count it needs. */
static fc_field point_data_field(const char *name, uint64_t *components)
{
    static const char *const velocity[] = { "velocity", "velocities", "vel", "v", "u" };
    static const char *const density[] = { "density", "rho", "dens" };
    static const char *const ids[] = { "id", "ids", "idp", "pid", "particleid", "particle_id", "particleids" };
    static const char *const radius[] = { "radius", "pscale" };
    fc_span n = { name, strlen(name) };
    for (size_t i = 0; i < sizeof velocity / sizeof velocity[0]; i++)
        if (fc_span_iequals(n, velocity[i]))
            return *components = 3, FC_FIELD_VX;
    for (size_t i = 0; i < sizeof density / sizeof density[0]; i++)
        if (fc_span_iequals(n, density[i]))
            return *components = 1, FC_FIELD_DENSITY;
    for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++)
        if (fc_span_iequals(n, ids[i]))
            return *components = 1, FC_FIELD_ID;
    for (size_t i = 0; i < sizeof radius / sizeof radius[0]; i++)
        if (fc_span_iequals(n, radius[i]))
            return *components = 1, FC_FIELD_RADIUS;
    return FC_FIELD_NONE;
}

static void describe_array(vx_doc *d, vx_array *a, const XML_Char **attrs)
{
    const char *type = fc_vx_attribute(attrs, "type"), *format = fc_vx_attribute(attrs, "format");
    const char *components = fc_vx_attribute(attrs, "NumberOfComponents");
    a->components = 1;
    if (components != NULL && !parse_count(components, &a->components))
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': NumberOfComponents '%.30s' is not a count", a->name,
                          components);
    if (!fc_vx_scalar_type(type, &a->type))
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': type '%.30s' is not a numeric VTK type", a->name,
                          type ? type : "(none)");
    if (format != NULL && strcmp(format, "appended") == 0) {
        a->format = VX_APPENDED_FORMAT;
        if (!parse_count(fc_vx_attribute(attrs, "offset"), &a->offset))
            return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': appended without a non-negative offset", a->name);
    } else if (format != NULL && strcmp(format, "binary") == 0) {
        a->format = VX_BINARY;
    } else if (format != NULL && strcmp(format, "ascii") == 0) {
        a->format = VX_ASCII;
    } else {
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': format '%.30s' is not ascii, binary or appended",
                          a->name, format ? format : "(none)");
    }
    a->line = (size_t)XML_GetCurrentLineNumber(d->xml.parser);
    if (a->format != VX_APPENDED_FORMAT)
        d->collecting = a;
}

/* A DataArray directly in Points (the positions) or PointData (mapped by name, others ignored). */
static void on_data_array(vx_doc *d, vx_element parent, const XML_Char **attrs)
{
    const char *name = fc_vx_attribute(attrs, "Name");
    uint64_t wanted = 3;
    fc_field field = FC_FIELD_X;
    if (parent == VX_POINT_DATA)
        field = name ? point_data_field(name, &wanted) : FC_FIELD_NONE;
    else if (d->fields.present[FC_FIELD_X])
        return; /* Points holds one array */
    if (field == FC_FIELD_NONE)
        return;
    if (d->array_count == VX_ARRAYS) /* unreachable while each group is taken once; never write past */
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': more than %d arrays", name ? name : "Points",
                          VX_ARRAYS);
    vx_array *a = &d->arrays[d->array_count];
    snprintf(a->name, sizeof a->name, "%s", name ? name : "Points");
    a->first = field;
    for (uint64_t k = 0; k < wanted; k++) {
        if (!fc_field_set_add(&d->fields, (fc_field)(field + k)))
            return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s' gives %s a second time", a->name,
                              fc_field_name(field));
    }
    d->array_count++;
    describe_array(d, a, attrs);
    if (d->xml.code == FC_OK && a->components != wanted)
        fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s' has %llu components, %s needs %llu", a->name,
                   (unsigned long long)a->components, field == FC_FIELD_X ? "Points" : fc_field_name(field),
                   (unsigned long long)wanted);
}

static vx_element classify(const vx_doc *d, const char *name)
{
    vx_element parent = d->depth ? d->stack[d->depth - 1] : VX_OTHER;
    if (d->depth == 0)
        return strcmp(name, "VTKFile") == 0 ? VX_FILE : VX_OTHER;
    if (parent == VX_FILE && (strcmp(name, "UnstructuredGrid") == 0 || strcmp(name, "PolyData") == 0))
        return VX_DATASET;
    if (parent == VX_FILE && strcmp(name, "AppendedData") == 0)
        return VX_APPENDED;
    if (parent == VX_DATASET && strcmp(name, "Piece") == 0)
        return VX_PIECE;
    if (parent == VX_PIECE && strcmp(name, "Points") == 0)
        return VX_POINTS;
    if (parent == VX_PIECE && strcmp(name, "PointData") == 0)
        return VX_POINT_DATA;
    if ((parent == VX_POINTS || parent == VX_POINT_DATA) && strcmp(name, "DataArray") == 0)
        return VX_DATA_ARRAY;
    return VX_OTHER;
}

static void XMLCALL on_start(void *user, const XML_Char *name, const XML_Char **attrs)
{
    vx_doc *d = user;
    if (d->depth == VX_MAX_DEPTH)
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "elements nested more than %d deep", VX_MAX_DEPTH);
    vx_element kind = classify(d, name);
    if (d->depth == 0 && kind != VX_FILE)
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "root element '%.40s' is not VTKFile", name);
    d->collecting = NULL; /* text of nested elements (InformationKey) is not the array's */
    if (kind == VX_FILE)
        on_file(d, attrs);
    else if (kind == VX_PIECE)
        on_piece(d, attrs);
    else if (kind == VX_DATA_ARRAY)
        on_data_array(d, d->stack[d->depth - 1], attrs);
    else if (kind == VX_APPENDED)
        fc_vx_on_appended(&d->xml, attrs);
    d->stack[d->depth++] = kind;
}

static void XMLCALL on_end(void *user, const XML_Char *name)
{
    vx_doc *d = user;
    (void)name;
    d->collecting = NULL;
    if (d->depth > 0)
        d->depth--;
}

static void XMLCALL on_text(void *user, const XML_Char *text, int len)
{
    vx_doc *d = user;
    vx_array *a = d->collecting;
    if (a != NULL && len > 0 && !fc_vx_text_append(&a->text, &a->text_len, &a->text_cap, text, (size_t)len))
        fc_vx_fail(&d->xml, FC_ERR_NOMEM, "DataArray '%s': cannot allocate memory for %zu bytes of text", a->name,
                   a->text_len + (size_t)len);
}

/* ---- the arrays ---- */

static fc_code store_values(const vx_doc *d, const vx_array *a, uint64_t index, double value, fc_frame *frame)
{
    uint64_t particle = index / a->components;
    fc_field field = (fc_field)(a->first + index % a->components);
    bool stored = a->type == FC_SCALAR_F64 ? fc_field_store_position64(d->xml.c, frame, particle, field, value)
                                           : fc_field_store(frame, particle, field, value);
    if (stored)
        return FC_OK;
    const char *requirement = fc_field_requirement(field);
    return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: DataArray '%s': particle %llu: %s = %g is not %s",
                        d->xml.c->name, a->name, (unsigned long long)particle, fc_field_name(field), value,
                        requirement);
}

static fc_code read_ascii(const vx_doc *d, const vx_array *a, uint64_t values, fc_frame *frame)
{
    fc_span rest = { a->text ? a->text : "", a->text_len }, token;
    for (uint64_t i = 0; i < values; i++) {
        double value;
        if (!fc_span_next_token(&rest, &token))
            return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s': %llu values, expected %llu",
                                d->xml.c->name, a->line, a->name, (unsigned long long)i, (unsigned long long)values);
        if (!fc_span_to_double(token, &value)) {
            char quoted[FC_QUOTE_MAX];
            return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s': '%s' is not a number",
                                d->xml.c->name, a->line, a->name, fc_span_quote(token, quoted, sizeof quoted));
        }
        fc_code code = store_values(d, a, i, value, frame);
        if (code != FC_OK)
            return code;
    }
    if (fc_span_next_token(&rest, &token))
        return fc_error_set(d->xml.err, FC_ERR_PARSE,
                            "%s: line %zu: DataArray '%s': more than the %llu values expected",
                            d->xml.c->name, a->line, a->name, (unsigned long long)values);
    return FC_OK;
}

static fc_code read_binary(const vx_doc *d, const vx_array *a, const uint8_t *appended, size_t appended_size,
                           uint64_t values, fc_frame *frame)
{
    size_t value_size = fc_scalar_size(a->type);
    if (values > SIZE_MAX / value_size)
        return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: DataArray '%s': %llu values overflow", d->xml.c->name,
                            a->name, (unsigned long long)values);
    fc_vx_source source;
    if (a->format == VX_BINARY) {
        fc_vx_source_init(&source, (const uint8_t *)a->text, a->text_len, true);
    } else {
        if (a->offset > appended_size)
            return fc_error_set(d->xml.err, FC_ERR_PARSE,
                                "%s: DataArray '%s': offset %llu is past the appended data's %zu bytes",
                                d->xml.c->name, a->name, (unsigned long long)a->offset, appended_size);
        fc_vx_source_init(&source, appended + a->offset, appended_size - (size_t)a->offset, d->xml.appended_base64);
    }
    char what[VX_NAME_MAX + 32];
    snprintf(what, sizeof what, "DataArray '%s'", a->name);
    uint8_t *bytes = NULL;
    fc_code code = fc_vx_read_block(&source, &d->xml.encoding, (size_t)values * value_size, d->xml.c->name, what,
                                    &bytes, d->xml.err);
    fc_cursor c;
    fc_cursor_init(&c, bytes, (size_t)values * value_size, d->xml.c->name);
    for (uint64_t i = 0; code == FC_OK && i < values; i++) {
        double value = 0.0;
        fc_cursor_read_scalar(&c, a->type, d->xml.encoding.big_endian, &value); /* the block holds exactly the values */
        code = store_values(d, a, i, value, frame);
    }
    free(bytes);
    return code;
}

/* The most values an array's bytes could hold: one character per ascii value, 3 bytes per 4 of base64, and
 * deflate's 1032:1 for compressed data. Checked before the frame is allocated for NumberOfPoints. */
static uint64_t most_values(const vx_doc *d, const vx_array *a, size_t appended_size)
{
    if (a->format == VX_ASCII)
        return a->text_len;
    uint64_t bytes = a->format == VX_BINARY ? a->text_len : appended_size;
    if (a->format == VX_BINARY || d->xml.appended_base64)
        bytes = bytes / 4 * 3 + 3;
    if (d->xml.encoding.compressed)
        bytes = bytes > UINT64_MAX / 1032 ? UINT64_MAX : bytes * 1032;
    return bytes / fc_scalar_size(a->type);
}

static fc_code check_sizes(const vx_doc *d, const uint8_t *appended, size_t appended_size)
{
    for (size_t i = 0; i < d->array_count; i++) {
        const vx_array *a = &d->arrays[i];
        if (a->format == VX_APPENDED_FORMAT && appended == NULL)
            return fc_error_set(d->xml.err, FC_ERR_PARSE,
                                "%s: line %zu: DataArray '%s' is appended but the file has no AppendedData",
                                d->xml.c->name, a->line, a->name);
        uint64_t most = most_values(d, a, appended_size);
        if (d->points > most / a->components)
            return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s': NumberOfPoints %llu x %llu "
                                "components cannot fit in its data (at most %llu values)", d->xml.c->name, a->line,
                                a->name, (unsigned long long)d->points, (unsigned long long)a->components,
                                (unsigned long long)most);
    }
    return FC_OK;
}

static fc_code read_arrays(vx_doc *d, const uint8_t *appended, size_t appended_size, fc_frame *frame)
{
    uint32_t attributes = 0;
    const char *missing = NULL;
    if (d->pieces == 0 || !d->fields.present[FC_FIELD_X])
        return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: no Piece with Points found", d->xml.c->name);
    if (!fc_field_set_attributes(&d->fields, &attributes, &missing))
        return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: %s", d->xml.c->name, missing);
    fc_code code = check_sizes(d, appended, appended_size);
    if (code == FC_OK)
        code = fc_reader_alloc_frame(d->xml.c, frame, d->points, attributes, d->xml.err);
    for (size_t i = 0; code == FC_OK && i < d->array_count; i++) {
        const vx_array *a = &d->arrays[i];
        uint64_t values = d->points * a->components; /* components <= 3, points < 2^62 once allocated */
        code = a->format == VX_ASCII ? read_ascii(d, a, values, frame)
                                     : read_binary(d, a, appended, appended_size, values, frame);
    }
    return code;
}

fc_code fc_read_vtkxml(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    vx_doc *d = calloc(1, sizeof *d);
    if (d == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: cannot allocate the reader's state", c->name);
    d->xml.c = c;
    d->xml.err = err;
    const uint8_t *appended;
    size_t appended_size;
    fc_code code = fc_vx_parse(&d->xml, on_start, on_end, on_text, d, &appended, &appended_size);
    if (code == FC_OK)
        code = read_arrays(d, appended, appended_size, frame);
    for (size_t i = 0; i < VX_ARRAYS; i++)
        free(d->arrays[i].text);
    free(d);
    return code;
}
