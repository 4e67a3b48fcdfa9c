/* reader_vtkxml.c — VTK XML UnstructuredGrid (.vtu) and PolyData (.vtp) files,
 * as ParaView, GPUSPH, PySPH and VTK's own writers produce them.
 *
 * The XML is parsed with expat. The particles are the Piece's Points; point
 * data arrays named like velocity, density or an id fill the frame's other
 * fields. DataArrays are "ascii" text, inline "binary" (base64) or "appended"
 * at an offset into the AppendedData section, which is base64 or raw bytes.
 * Raw appended bytes make the file invalid XML, so expat sees the file only up
 * to the AppendedData start tag, and the arrays are read from the bytes after
 * its '_' by offset. Binary data carries VTK's header (UInt32 or UInt64 words, in
 * the file's byte order) and may be in vtkZLibDataCompressor blocks
 * (reader_vtkxml_data.c). Cells and other arrays are not read. */
#include "reader_formats.h"

#include <expat.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "reader_fields.h"
#include "reader_vtkxml_data.h"

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
    const fc_cursor *c;
    fc_error *err;
    fc_code code;
    XML_Parser parser;
    size_t depth;
    vx_element stack[VX_MAX_DEPTH];
    bool have_file, big_endian, header64, compressed;
    size_t pieces;
    uint64_t points;
    vx_array arrays[VX_ARRAYS];
    size_t array_count;
    vx_array *collecting; /* the inline DataArray whose text is being gathered */
    bool have_appended, appended_base64;
    fc_field_set fields;
} vx_doc;

/* ---- attributes and errors from inside expat's callbacks ---- */

/* Records the first error (with the XML line) and stops the parser. */
static void vx_fail(vx_doc *d, fc_code code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void vx_fail(vx_doc *d, fc_code code, const char *fmt, ...)
{
    if (d->code != FC_OK)
        return;
    char reason[FC_ERROR_MESSAGE_MAX];
    va_list args;
    va_start(args, fmt);
    vsnprintf(reason, sizeof reason, fmt, args);
    va_end(args);
    d->code = fc_error_set(d->err, code, "%s: line %lu: %s", d->c->name,
                           (unsigned long)XML_GetCurrentLineNumber(d->parser), reason);
    XML_StopParser(d->parser, XML_FALSE);
}

static bool parse_count(const char *text, uint64_t *out)
{
    return text != NULL && fc_span_to_count(fc_span_trim((fc_span){ text, strlen(text) }), out);
}

/* ---- elements ---- */

static void on_file(vx_doc *d, const XML_Char **attrs)
{
    const char *type = fc_vx_attribute(attrs, "type"), *order = fc_vx_attribute(attrs, "byte_order");
    const char *header = fc_vx_attribute(attrs, "header_type"), *compressor = fc_vx_attribute(attrs, "compressor");
    if (type == NULL || (strcmp(type, "UnstructuredGrid") != 0 && strcmp(type, "PolyData") != 0)) {
        if (type != NULL && strcmp(type, "Collection") == 0)
            return vx_fail(d, FC_ERR_PARSE, "a .pvd collection, not a dataset: name it .pvd, or give one of its files");
        return vx_fail(d, FC_ERR_PARSE, "VTKFile type '%.40s' is not a particle dataset (UnstructuredGrid .vtu or "
                                        "PolyData .vtp)", type ? type : "(none)");
    }
    d->big_endian = order != NULL && strcmp(order, "BigEndian") == 0;
    if (order != NULL && !d->big_endian && strcmp(order, "LittleEndian") != 0)
        return vx_fail(d, FC_ERR_PARSE, "byte_order '%.40s' is neither LittleEndian nor BigEndian", order);
    d->header64 = header != NULL && strcmp(header, "UInt64") == 0;
    if (header != NULL && !d->header64 && strcmp(header, "UInt32") != 0)
        return vx_fail(d, FC_ERR_PARSE, "header_type '%.40s' is neither UInt32 nor UInt64", header);
    d->compressed = compressor != NULL && compressor[0] != '\0';
    if (d->compressed && strcmp(compressor, "vtkZLibDataCompressor") != 0)
        return vx_fail(d, FC_ERR_PARSE, "compressor '%.40s' is not supported (only vtkZLibDataCompressor: write with "
                                        "SetCompressorTypeToZLib or none)", compressor);
    d->have_file = true;
}

static void on_piece(vx_doc *d, const XML_Char **attrs)
{
    if (++d->pieces > 1)
        return vx_fail(d, FC_ERR_PARSE, "a second Piece: only single-piece files are read (merge the pieces or give "
                                        "the piece files one by one)");
    if (!parse_count(fc_vx_attribute(attrs, "NumberOfPoints"), &d->points))
        return vx_fail(d, FC_ERR_PARSE, "Piece lacks a non-negative integer NumberOfPoints");
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
        return vx_fail(d, FC_ERR_PARSE, "DataArray '%s': NumberOfComponents '%.30s' is not a count", a->name, components);
    if (!fc_vx_scalar_type(type, &a->type))
        return vx_fail(d, FC_ERR_PARSE, "DataArray '%s': type '%.30s' is not a numeric VTK type", a->name,
                       type ? type : "(none)");
    if (format != NULL && strcmp(format, "appended") == 0) {
        a->format = VX_APPENDED_FORMAT;
        if (!parse_count(fc_vx_attribute(attrs, "offset"), &a->offset))
            return vx_fail(d, FC_ERR_PARSE, "DataArray '%s': appended without a non-negative offset", a->name);
    } else if (format != NULL && strcmp(format, "binary") == 0) {
        a->format = VX_BINARY;
    } else if (format != NULL && strcmp(format, "ascii") == 0) {
        a->format = VX_ASCII;
    } else {
        return vx_fail(d, FC_ERR_PARSE, "DataArray '%s': format '%.30s' is not ascii, binary or appended", a->name,
                       format ? format : "(none)");
    }
    a->line = (size_t)XML_GetCurrentLineNumber(d->parser);
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
        return vx_fail(d, FC_ERR_PARSE, "DataArray '%s': more than %d arrays", name ? name : "Points", VX_ARRAYS);
    vx_array *a = &d->arrays[d->array_count];
    snprintf(a->name, sizeof a->name, "%s", name ? name : "Points");
    a->first = field;
    for (uint64_t k = 0; k < wanted; k++) {
        if (!fc_field_set_add(&d->fields, (fc_field)(field + k)))
            return vx_fail(d, FC_ERR_PARSE, "DataArray '%s' gives %s a second time", a->name, fc_field_name(field));
    }
    d->array_count++;
    describe_array(d, a, attrs);
    if (d->code == FC_OK && a->components != wanted)
        vx_fail(d, FC_ERR_PARSE, "DataArray '%s' has %llu components, %s needs %llu", a->name,
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
        return vx_fail(d, FC_ERR_PARSE, "elements nested more than %d deep", VX_MAX_DEPTH);
    vx_element kind = classify(d, name);
    if (d->depth == 0 && kind != VX_FILE)
        return vx_fail(d, FC_ERR_PARSE, "root element '%.40s' is not VTKFile", name);
    d->collecting = NULL; /* text of nested elements (InformationKey) is not the array's */
    if (kind == VX_FILE)
        on_file(d, attrs);
    else if (kind == VX_PIECE)
        on_piece(d, attrs);
    else if (kind == VX_DATA_ARRAY)
        on_data_array(d, d->stack[d->depth - 1], attrs);
    else if (kind == VX_APPENDED) {
        const char *encoding = fc_vx_attribute(attrs, "encoding");
        d->have_appended = true;
        d->appended_base64 = encoding == NULL || strcmp(encoding, "base64") == 0;
        if (!d->appended_base64 && strcmp(encoding, "raw") != 0)
            vx_fail(d, FC_ERR_PARSE, "AppendedData encoding '%.30s' is neither raw nor base64", encoding);
    }
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
        vx_fail(d, FC_ERR_NOMEM, "DataArray '%s': cannot allocate memory for %zu bytes of text", a->name,
                a->text_len + (size_t)len);
}

/* ---- the XML part ---- */

static fc_code parse_xml(vx_doc *d, const uint8_t *data, size_t size, bool complete)
{
    d->parser = XML_ParserCreate(NULL);
    if (d->parser == NULL)
        return fc_error_set(d->err, FC_ERR_NOMEM, "%s: cannot create the XML parser", d->c->name);
    XML_SetUserData(d->parser, d);
    XML_SetElementHandler(d->parser, on_start, on_end);
    XML_SetCharacterDataHandler(d->parser, on_text);
    size_t done = 0;
    enum XML_Status status = XML_STATUS_OK;
    do { /* expat takes int lengths: feed large files in pieces */
        size_t piece = size - done > INT_MAX / 2 ? INT_MAX / 2 : size - done;
        bool last = complete && done + piece == size;
        status = XML_Parse(d->parser, (const char *)data + done, (int)piece, last);
        done += piece;
    } while (status == XML_STATUS_OK && done < size);
    if (status == XML_STATUS_ERROR && d->code == FC_OK)
        d->code = fc_error_set(d->err, FC_ERR_PARSE, "%s: line %lu: XML: %s", d->c->name,
                               (unsigned long)XML_GetCurrentLineNumber(d->parser),
                               XML_ErrorString(XML_GetErrorCode(d->parser)));
    XML_ParserFree(d->parser);
    d->parser = NULL;
    return d->code;
}

/* ---- the arrays ---- */

static fc_code store_values(const vx_doc *d, const vx_array *a, uint64_t index, double value, fc_frame *frame)
{
    uint64_t particle = index / a->components;
    fc_field field = (fc_field)(a->first + index % a->components);
    bool stored = a->type == FC_SCALAR_F64 ? fc_field_store_position64(d->c, frame, particle, field, value)
                                           : fc_field_store(frame, particle, field, value);
    if (stored)
        return FC_OK;
    const char *requirement = fc_field_requirement(field);
    return fc_error_set(d->err, FC_ERR_PARSE, "%s: DataArray '%s': particle %llu: %s = %g is not %s", d->c->name,
                        a->name, (unsigned long long)particle, fc_field_name(field), value, requirement);
}

static fc_code read_ascii(const vx_doc *d, const vx_array *a, uint64_t values, fc_frame *frame)
{
    fc_span rest = { a->text ? a->text : "", a->text_len }, token;
    for (uint64_t i = 0; i < values; i++) {
        double value;
        if (!fc_span_next_token(&rest, &token))
            return fc_error_set(d->err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s': %llu values, expected %llu",
                                d->c->name, a->line, a->name, (unsigned long long)i, (unsigned long long)values);
        if (!fc_span_to_double(token, &value)) {
            char quoted[FC_QUOTE_MAX];
            return fc_error_set(d->err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s': '%s' is not a number",
                                d->c->name, a->line, a->name, fc_span_quote(token, quoted, sizeof quoted));
        }
        fc_code code = store_values(d, a, i, value, frame);
        if (code != FC_OK)
            return code;
    }
    if (fc_span_next_token(&rest, &token))
        return fc_error_set(d->err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s': more than the %llu values expected",
                            d->c->name, a->line, a->name, (unsigned long long)values);
    return FC_OK;
}

static fc_code read_binary(const vx_doc *d, const vx_array *a, const uint8_t *appended, size_t appended_size,
                           uint64_t values, fc_frame *frame)
{
    size_t value_size = fc_scalar_size(a->type);
    if (values > SIZE_MAX / value_size)
        return fc_error_set(d->err, FC_ERR_PARSE, "%s: DataArray '%s': %llu values overflow", d->c->name, a->name,
                            (unsigned long long)values);
    fc_vx_source source;
    if (a->format == VX_BINARY) {
        fc_vx_source_init(&source, (const uint8_t *)a->text, a->text_len, true);
    } else {
        if (a->offset > appended_size)
            return fc_error_set(d->err, FC_ERR_PARSE, "%s: DataArray '%s': offset %llu is past the appended data's %zu bytes",
                                d->c->name, a->name, (unsigned long long)a->offset, appended_size);
        fc_vx_source_init(&source, appended + a->offset, appended_size - (size_t)a->offset, d->appended_base64);
    }
    char what[VX_NAME_MAX + 32];
    snprintf(what, sizeof what, "DataArray '%s'", a->name);
    fc_vx_encoding encoding = { d->header64, d->big_endian, d->compressed };
    uint8_t *bytes = NULL;
    fc_code code = fc_vx_read_block(&source, &encoding, (size_t)values * value_size, d->c->name, what, &bytes, d->err);
    fc_cursor c;
    fc_cursor_init(&c, bytes, (size_t)values * value_size, d->c->name);
    for (uint64_t i = 0; code == FC_OK && i < values; i++) {
        double value = 0.0;
        fc_cursor_read_scalar(&c, a->type, d->big_endian, &value); /* the block holds exactly the values */
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
    if (a->format == VX_BINARY || d->appended_base64)
        bytes = bytes / 4 * 3 + 3;
    if (d->compressed)
        bytes = bytes > UINT64_MAX / 1032 ? UINT64_MAX : bytes * 1032;
    return bytes / fc_scalar_size(a->type);
}

static fc_code check_sizes(const vx_doc *d, const uint8_t *appended, size_t appended_size)
{
    for (size_t i = 0; i < d->array_count; i++) {
        const vx_array *a = &d->arrays[i];
        if (a->format == VX_APPENDED_FORMAT && appended == NULL)
            return fc_error_set(d->err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s' is appended but the file has no "
                                "AppendedData", d->c->name, a->line, a->name);
        uint64_t most = most_values(d, a, appended_size);
        if (d->points > most / a->components)
            return fc_error_set(d->err, FC_ERR_PARSE, "%s: line %zu: DataArray '%s': NumberOfPoints %llu x %llu "
                                "components cannot fit in its data (at most %llu values)", d->c->name, a->line, a->name,
                                (unsigned long long)d->points, (unsigned long long)a->components,
                                (unsigned long long)most);
    }
    return FC_OK;
}

static fc_code read_arrays(vx_doc *d, const uint8_t *appended, size_t appended_size, fc_frame *frame)
{
    uint32_t attributes = 0;
    const char *missing = NULL;
    if (d->pieces == 0 || !d->fields.present[FC_FIELD_X])
        return fc_error_set(d->err, FC_ERR_PARSE, "%s: no Piece with Points found", d->c->name);
    if (!fc_field_set_attributes(&d->fields, &attributes, &missing))
        return fc_error_set(d->err, FC_ERR_PARSE, "%s: %s", d->c->name, missing);
    fc_code code = check_sizes(d, appended, appended_size);
    if (code == FC_OK)
        code = fc_reader_alloc_frame(d->c, frame, d->points, attributes, d->err);
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
    d->c = c;
    d->err = err;
    size_t xml_size = 0;
    const uint8_t *appended = fc_vx_find_appended(c->data, c->size, &xml_size);
    fc_code code = parse_xml(d, c->data, xml_size, appended == NULL);
    if (code == FC_OK && !d->have_file)
        code = fc_error_set(err, FC_ERR_PARSE, "%s: no VTKFile element", c->name);
    if (code == FC_OK && appended != NULL && !d->have_appended)
        code = fc_error_set(err, FC_ERR_PARSE, "%s: AppendedData is not a child of VTKFile", c->name);
    if (code == FC_OK && appended != NULL) {
        /* Data starts after the '_' that marks it; whitespace may come before it. */
        size_t left = c->size - (size_t)(appended - c->data);
        while (left > 0 && *appended != '_' && (*appended == ' ' || *appended == '\n' || *appended == '\r' ||
                                                *appended == '\t'))
            appended++, left--;
        if (left == 0 || *appended != '_')
            code = fc_error_set(err, FC_ERR_PARSE, "%s: AppendedData does not start with '_'", c->name);
        else
            code = read_arrays(d, appended + 1, left - 1, frame);
    } else if (code == FC_OK) {
        code = read_arrays(d, NULL, 0, frame);
    }
    for (size_t i = 0; i < VX_ARRAYS; i++)
        free(d->arrays[i].text);
    free(d);
    return code;
}
