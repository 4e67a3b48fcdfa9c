/* mesh_vtp.c — VTK XML PolyData (.vtp): the single Piece's Points and its
 * Polys (connectivity + offsets, VTK's end offsets), polygons fanned into
 * triangles. The XML part (expat, up to AppendedData: raw appended bytes are not
 * XML) is the particle reader's reader_vtkxml_xml.h and DataArray bytes are
 * decoded by its reader_vtkxml_data.h (base64 or raw, UInt32/UInt64 headers,
 * zlib blocks), so both readers accept the same files and encodings. Point
 * Normals and other arrays are skipped (MESH carries positions and triangles
 * only). Strips-, Lines- or Verts-only files and several pieces are refused
 * with a reason. */
#include "mesh_formats.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "reader_vtkxml_data.h"
#include "reader_vtkxml_xml.h"

enum { VP_POINTS, VP_CONNECTIVITY, VP_OFFSETS, VP_ARRAYS };
enum { VP_MAX_DEPTH = 64, VP_MAX_CORNERS = 4096 };

typedef enum vp_format { VP_ASCII, VP_BINARY, VP_APPENDED } vp_format;

typedef struct vp_array {
    bool present;
    fc_scalar_type type;
    uint64_t components;
    vp_format format;
    uint64_t offset;
    char *text;
    size_t text_len, text_cap;
} vp_array;

typedef struct vp_doc {
    fc_vx_xml xml; /* the file, its first error, its encoding */
    size_t depth;
    char stack[VP_MAX_DEPTH][12]; /* element names that matter, "" for others */
    size_t pieces;
    uint64_t points, polys, strips, lines;
    vp_array arrays[VP_ARRAYS];
    vp_array *collecting;
} vp_doc;

static const char *const array_names[VP_ARRAYS] = {"Points", "connectivity", "offsets"};

/* An absent count is 0 (VTK omits none, but hand-written files may). */
static bool count_attribute(const XML_Char **attrs, const char *name, uint64_t *out)
{
    const char *text = fc_vx_attribute(attrs, name);
    *out = 0;
    return text == NULL || fc_span_to_count(fc_span_trim((fc_span){text, strlen(text)}), out);
}

static void on_file(vp_doc *d, const XML_Char **attrs)
{
    const char *type = fc_vx_attribute(attrs, "type");
    if (type == NULL || strcmp(type, "PolyData") != 0)
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "VTKFile type '%.40s' is not PolyData", type ? type : "(none)");
    fc_vx_on_file(&d->xml, attrs);
}

static void on_piece(vp_doc *d, const XML_Char **attrs)
{
    if (++d->pieces > 1)
        return fc_vx_fail(&d->xml, FC_ERR_PARSE,
                          "a second Piece: only single-piece .vtp meshes are read (merge the pieces)");
    if (!count_attribute(attrs, "NumberOfPoints", &d->points) || !count_attribute(attrs, "NumberOfPolys", &d->polys) ||
        !count_attribute(attrs, "NumberOfStrips", &d->strips) || !count_attribute(attrs, "NumberOfLines", &d->lines))
        return fc_vx_fail(&d->xml, FC_ERR_PARSE,
                          "Piece: NumberOfPoints/Polys/Strips/Lines must be non-negative integers");
}

static void on_data_array(vp_doc *d, int which, const XML_Char **attrs)
{
    vp_array *a = &d->arrays[which];
    if (a->present)
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "a second '%s' DataArray", array_names[which]);
    a->present = true;
    const char *format = fc_vx_attribute(attrs, "format"), *components = fc_vx_attribute(attrs, "NumberOfComponents");
    a->components = 1;
    if (components != NULL && !fc_span_to_count(fc_span_trim((fc_span){components, strlen(components)}),
                                                &a->components))
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': NumberOfComponents is not a count",
                          array_names[which]);
    if (a->components != (which == VP_POINTS ? 3u : 1u))
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s' has %llu components, expected %u", array_names[which],
                          (unsigned long long)a->components, which == VP_POINTS ? 3u : 1u);
    if (!fc_vx_scalar_type(fc_vx_attribute(attrs, "type"), &a->type))
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': type is not a numeric VTK type", array_names[which]);
    if (format != NULL && strcmp(format, "appended") == 0) {
        a->format = VP_APPENDED;
        if (!count_attribute(attrs, "offset", &a->offset) || fc_vx_attribute(attrs, "offset") == NULL)
            return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': appended without a non-negative offset",
                              array_names[which]);
    } else if (format != NULL && (strcmp(format, "binary") == 0 || strcmp(format, "ascii") == 0)) {
        a->format = format[0] == 'b' ? VP_BINARY : VP_ASCII;
        d->collecting = a;
    } else {
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "DataArray '%s': format '%.30s' is not ascii, binary or appended",
                          array_names[which], format ? format : "(none)");
    }
}

/* Elements are told apart by their parent: VTKFile/PolyData/Piece/{Points,Polys}/DataArray. */
static void XMLCALL on_start(void *user, const XML_Char *name, const XML_Char **attrs)
{
    vp_doc *d = user;
    if (d->depth == VP_MAX_DEPTH)
        return fc_vx_fail(&d->xml, FC_ERR_PARSE, "elements nested more than %d deep", VP_MAX_DEPTH);
    const char *parent = d->depth ? d->stack[d->depth - 1] : NULL;
    const char *kind = "";
    d->collecting = NULL;
    if (parent == NULL) {
        if (strcmp(name, "VTKFile") != 0)
            return fc_vx_fail(&d->xml, FC_ERR_PARSE, "root element '%.40s' is not VTKFile", name);
        kind = "VTKFile";
        on_file(d, attrs);
    } else if (strcmp(parent, "VTKFile") == 0 && strcmp(name, "PolyData") == 0) {
        kind = "PolyData";
    } else if (strcmp(parent, "VTKFile") == 0 && strcmp(name, "AppendedData") == 0) {
        fc_vx_on_appended(&d->xml, attrs);
    } else if (strcmp(parent, "PolyData") == 0 && strcmp(name, "Piece") == 0) {
        kind = "Piece";
        on_piece(d, attrs);
    } else if (strcmp(parent, "Piece") == 0 && (strcmp(name, "Points") == 0 || strcmp(name, "Polys") == 0)) {
        kind = name[1] == 'o' && name[2] == 'i' ? "Points" : "Polys";
    } else if (strcmp(name, "DataArray") == 0 && strcmp(parent, "Points") == 0) {
        on_data_array(d, VP_POINTS, attrs);
    } else if (strcmp(name, "DataArray") == 0 && strcmp(parent, "Polys") == 0) {
        const char *array = fc_vx_attribute(attrs, "Name");
        if (array != NULL && strcmp(array, "connectivity") == 0)
            on_data_array(d, VP_CONNECTIVITY, attrs);
        else if (array != NULL && strcmp(array, "offsets") == 0)
            on_data_array(d, VP_OFFSETS, attrs);
    }
    snprintf(d->stack[d->depth++], sizeof d->stack[0], "%s", kind);
}

static void XMLCALL on_end(void *user, const XML_Char *name)
{
    vp_doc *d = user;
    (void)name;
    d->collecting = NULL;
    if (d->depth > 0)
        d->depth--;
}

static void XMLCALL on_text(void *user, const XML_Char *text, int len)
{
    vp_doc *d = user;
    vp_array *a = d->collecting;
    if (a != NULL && len > 0 && !fc_vx_text_append(&a->text, &a->text_len, &a->text_cap, text, (size_t)len))
        fc_vx_fail(&d->xml, FC_ERR_NOMEM, "out of memory for DataArray text");
}

/* The most values an array's bytes could hold (ascii: one per character; base64 3:4; deflate 1032:1), checked
 * before anything is allocated for a count the file claims. */
static uint64_t most_values(const vp_doc *d, const vp_array *a, size_t appended_size)
{
    if (a->format == VP_ASCII)
        return a->text_len;
    uint64_t bytes = a->format == VP_BINARY ? a->text_len : appended_size;
    if (a->format == VP_BINARY || d->xml.appended_base64)
        bytes = bytes / 4 * 3 + 3;
    if (d->xml.encoding.compressed)
        bytes = bytes > UINT64_MAX / 1032 ? UINT64_MAX : bytes * 1032;
    return bytes / fc_scalar_size(a->type);
}

/* `count` values of array `which` as doubles (malloc'd *out). */
static fc_code read_values(const vp_doc *d, int which, const uint8_t *appended, size_t appended_size, uint64_t count,
                           double **out)
{
    const vp_array *a = &d->arrays[which];
    const char *name = d->xml.c->name, *what = array_names[which];
    *out = NULL;
    if (a->format == VP_APPENDED && appended == NULL)
        return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: DataArray '%s' is appended but the file has no AppendedData",
                            name, what);
    if (count > most_values(d, a, appended_size))
        return fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: DataArray '%s': %llu values cannot fit in its data", name,
                            what, (unsigned long long)count);
    double *values = malloc((count ? count : 1) * sizeof *values);
    if (values == NULL)
        return fc_error_set(d->xml.err, FC_ERR_NOMEM, "%s: out of memory for DataArray '%s'", name, what);
    fc_code code = FC_OK;
    if (a->format == VP_ASCII) {
        fc_span rest = {a->text ? a->text : "", a->text_len}, token;
        for (uint64_t i = 0; code == FC_OK && i < count; i++)
            if (!fc_span_next_token(&rest, &token) || !fc_span_to_double(token, &values[i]))
                code = fc_error_set(d->xml.err, FC_ERR_PARSE,
                                    "%s: DataArray '%s': value %llu is missing or not a number",
                                    name, what, (unsigned long long)i);
        if (code == FC_OK && fc_span_next_token(&rest, &token))
            code = fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: DataArray '%s': more than the %llu values expected",
                                name, what, (unsigned long long)count);
    } else {
        fc_vx_source source;
        if (a->format == VP_BINARY)
            fc_vx_source_init(&source, (const uint8_t *)a->text, a->text_len, true);
        else if (a->offset <= appended_size)
            fc_vx_source_init(&source, appended + a->offset, appended_size - (size_t)a->offset, d->xml.appended_base64);
        else
            code = fc_error_set(d->xml.err, FC_ERR_PARSE, "%s: DataArray '%s': offset past the appended data", name,
                                what);
        size_t bytes_count = (size_t)count * fc_scalar_size(a->type);
        uint8_t *bytes = NULL;
        char label[48];
        snprintf(label, sizeof label, "DataArray '%s'", what);
        if (code == FC_OK)
            code = fc_vx_read_block(&source, &d->xml.encoding, bytes_count, name, label, &bytes, d->xml.err);
        fc_cursor c;
        fc_cursor_init(&c, bytes, code == FC_OK ? bytes_count : 0, name);
        for (uint64_t i = 0; code == FC_OK && i < count; i++)
            fc_cursor_read_scalar(&c, a->type, d->xml.encoding.big_endian, &values[i]); /* the block holds them */
        free(bytes);
    }
    if (code != FC_OK) {
        free(values);
        return code;
    }
    *out = values;
    return FC_OK;
}

/* The Polys' cells as polygons: offsets are each cell's end in connectivity, increasing from 0. */
static fc_code add_polygons(const vp_doc *d, fc_mesh_builder *b, const double *offsets, const double *connectivity,
                            fc_error *err)
{
    uint64_t corners[VP_MAX_CORNERS];
    uint64_t start = 0;
    for (uint64_t cell = 0; cell < d->polys; cell++) {
        uint64_t end = (uint64_t)offsets[cell]; /* checked in range by read_mesh_arrays */
        if (end - start > VP_MAX_CORNERS)
            return fc_cursor_fail(d->xml.c, err, "Polys cell %llu has more than %d corners", (unsigned long long)cell,
                                  VP_MAX_CORNERS);
        for (uint64_t k = start; k < end; k++) {
            double v = connectivity[k];
            if (!(v >= 0 && v < (double)b->mesh.vertex_count) || v != (double)(uint64_t)v)
                return fc_cursor_fail(d->xml.c, err, "Polys connectivity[%llu] = %g is not a point index below %u",
                                      (unsigned long long)k, v, (unsigned)b->mesh.vertex_count);
            corners[k - start] = (uint64_t)v;
        }
        fc_code code = fc_mesh_builder_polygon(b, d->xml.c, corners, end - start, err);
        if (code != FC_OK)
            return code;
        start = end;
    }
    return FC_OK;
}

static fc_code read_mesh_arrays(vp_doc *d, const uint8_t *appended, size_t appended_size, fc_mesh_builder *b,
                                fc_error *err)
{
    const char *name = d->xml.c->name;
    if (d->pieces == 0 || !d->arrays[VP_POINTS].present)
        return fc_error_set(err, FC_ERR_PARSE, "%s: no Piece with Points found", name);
    if (d->polys == 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: the Piece has no Polys (%llu strips, %llu lines): only polygon "
                            "meshes are read (vtkTriangleFilter turns strips into triangles)", name,
                            (unsigned long long)d->strips, (unsigned long long)d->lines);
    if (!d->arrays[VP_CONNECTIVITY].present || !d->arrays[VP_OFFSETS].present)
        return fc_error_set(err, FC_ERR_PARSE, "%s: Polys lacks its connectivity or offsets DataArray", name);
    /* No reserve from the claimed counts: a short file must not make the reader allocate for them. */
    fc_code code = FC_OK;
    double *points = NULL, *offsets = NULL, *connectivity = NULL;
    if (d->points > UINT64_MAX / 3)
        code = fc_error_set(err, FC_ERR_PARSE, "%s: NumberOfPoints %llu overflows", name,
                            (unsigned long long)d->points);
    else
        code = read_values(d, VP_POINTS, appended, appended_size, 3 * d->points, &points);
    for (uint64_t i = 0; code == FC_OK && i < d->points; i++)
        code = fc_mesh_builder_vertex(b, d->xml.c, &points[3 * i], err);
    if (code == FC_OK)
        code = read_values(d, VP_OFFSETS, appended, appended_size, d->polys, &offsets);
    double previous = 0;
    for (uint64_t i = 0; code == FC_OK && i < d->polys; i++) {
        if (!(offsets[i] >= previous && offsets[i] <= 9007199254740992.0) || offsets[i] != (double)(uint64_t)offsets[i])
            code = fc_error_set(err, FC_ERR_PARSE, "%s: Polys offsets[%llu] = %g does not follow %g", name,
                                (unsigned long long)i, offsets[i], previous);
        else
            previous = offsets[i];
    }
    uint64_t corners_total = code == FC_OK ? (uint64_t)previous : 0;
    if (code == FC_OK)
        code = read_values(d, VP_CONNECTIVITY, appended, appended_size, corners_total, &connectivity);
    if (code == FC_OK)
        code = add_polygons(d, b, offsets, connectivity, err);
    free(points);
    free(offsets);
    free(connectivity);
    return code;
}

fc_code fc_read_mesh_vtp(fc_cursor *c, fc_mesh_builder *b, fc_error *err)
{
    vp_doc *d = calloc(1, sizeof *d);
    if (d == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", c->name);
    d->xml.c = c;
    d->xml.err = err;
    const uint8_t *appended;
    size_t appended_size;
    fc_code code = fc_vx_parse(&d->xml, on_start, on_end, on_text, d, &appended, &appended_size);
    if (code == FC_OK)
        code = read_mesh_arrays(d, appended, appended_size, b, err);
    for (int i = 0; i < VP_ARRAYS; i++)
        free(d->arrays[i].text);
    free(d);
    return code;
}
