/* mesh_vtk.c — legacy VTK POLYDATA: the header ("# vtk DataFile Version",
 * a title, ASCII or BINARY, DATASET POLYDATA), POINTS, then cell sections:
 * POLYGONS (polygons, fanned) and TRIANGLE_STRIPS (strips, each of its
 * triangles wound alike), VERTICES and LINES read past. Cells come as the
 * 4.x layout (SIZE numbers: a count, then that many point indices, per cell)
 * or the 5.1 layout (OFFSETS and CONNECTIVITY arrays). Binary data is
 * big-endian. The first POINT_DATA, CELL_DATA or FIELD ends the geometry. */
#include "mesh_formats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

#define MAX_CORNERS 4096u

typedef struct vtk_reader {
    fc_cursor *c;
    fc_mesh_builder *b;
    bool binary;
    uint64_t *corners;   /* MAX_CORNERS */
} vtk_reader;

static bool type_named(fc_span s, fc_scalar_type *out)
{
    static const struct {
        const char *name;
        fc_scalar_type type;
    } table[] = {{"unsigned_char", FC_SCALAR_U8},  {"char", FC_SCALAR_I8},          {"unsigned_short", FC_SCALAR_U16},
                 {"short", FC_SCALAR_I16},         {"unsigned_int", FC_SCALAR_U32}, {"int", FC_SCALAR_I32},
                 {"unsigned_long", FC_SCALAR_U64}, {"long", FC_SCALAR_I64},         {"vtktypeint64", FC_SCALAR_I64},
                 {"vtktypeuint64", FC_SCALAR_U64}, {"float", FC_SCALAR_F32},        {"double", FC_SCALAR_F64}};
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (fc_span_iequals(s, table[i].name)) {
            *out = table[i].type;
            return true;
        }
    return false;
}

static fc_code read_value(vtk_reader *r, fc_scalar_type type, double *out, fc_error *err)
{
    if (r->binary) {
        if (fc_cursor_read_scalar(r->c, type, true, out))
            return FC_OK;
        return fc_cursor_fail(r->c, err, "the binary data ends early");
    }
    fc_span token;
    if (fc_cursor_next_token(r->c, &token) && fc_span_to_double(token, out))
        return FC_OK;
    return fc_cursor_fail(r->c, err, "the data ends early or holds something that is not a number");
}

/* A non-negative integer value below `bound`. */
static fc_code read_index(vtk_reader *r, fc_scalar_type type, double bound, uint64_t *out, fc_error *err)
{
    double v;
    fc_code code = read_value(r, type, &v, err);
    if (code != FC_OK)
        return code;
    if (!(v >= 0.0 && v < bound) || v != floor(v))
        return fc_cursor_fail(r->c, err, "%g where an index or count below %g was expected", v, bound);
    *out = (uint64_t)v;
    return FC_OK;
}

/* Ends a binary block: the line break after it. */
static void after_block(vtk_reader *r)
{
    if (r->binary && fc_cursor_remaining(r->c) > 0 && r->c->data[r->c->pos] == '\n')
        r->c->pos++;
}

static fc_code read_points(vtk_reader *r, fc_span rest, fc_error *err)
{
    fc_span count_text, type_text;
    uint64_t count;
    fc_scalar_type type;
    if (!fc_span_next_token(&rest, &count_text) || !fc_span_to_count(count_text, &count) ||
        !fc_span_next_token(&rest, &type_text) || !type_named(type_text, &type))
        return fc_cursor_fail(r->c, err, "a POINTS line that is not \"POINTS N TYPE\"");
    fc_code code = fc_mesh_builder_reserve(r->b, r->c, count, 0, err);
    for (uint64_t i = 0; i < count && code == FC_OK; i++) {
        double xyz[3];
        for (int k = 0; k < 3 && code == FC_OK; k++)
            code = read_value(r, type, &xyz[k], err);
        if (code == FC_OK)
            code = fc_mesh_builder_vertex(r->b, r->c, xyz, err);
    }
    after_block(r);
    return code;
}

/* One cell of `n` point indices (in r->corners) as the section says. */
static fc_code add_cell(vtk_reader *r, bool strip, uint64_t n, fc_error *err)
{
    if (!strip)
        return fc_mesh_builder_polygon(r->b, r->c, r->corners, n, err);
    if (n < 3)
        return fc_cursor_fail(r->c, err, "a triangle strip of %llu points", (unsigned long long)n);
    for (uint64_t i = 0; i + 2 < n; i++) {
        /* Every other triangle of a strip is reversed, so all keep one winding. */
        uint64_t t[3] = {r->corners[i + (i % 2)], r->corners[i + 1 - (i % 2)], r->corners[i + 2]};
        fc_code code = fc_mesh_builder_polygon(r->b, r->c, t, 3, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

/* 4.x: `size` numbers, each cell a count and its indices. */
static fc_code read_cells_legacy(vtk_reader *r, uint64_t cells, uint64_t size, bool keep, bool strip, fc_error *err)
{
    uint64_t used = 0;
    fc_code code = FC_OK;
    for (uint64_t i = 0; i < cells && code == FC_OK; i++) {
        uint64_t n = 0;   /* read_index leaves it unset when it fails */
        code = read_index(r, FC_SCALAR_I32, MAX_CORNERS + 1.0, &n, err);
        for (uint64_t j = 0; j < n && code == FC_OK; j++)
            code = read_index(r, FC_SCALAR_I32, 4294967296.0, &r->corners[j], err);
        used += n + 1;
        if (code == FC_OK && used > size)
            code = fc_cursor_fail(r->c, err, "cells hold more numbers than the section's size %llu",
                                  (unsigned long long)size);
        if (code == FC_OK && keep)
            code = add_cell(r, strip, n, err);
    }
    if (code == FC_OK && used != size)
        code = fc_cursor_fail(r->c, err, "cells hold %llu numbers, the section's size says %llu",
                              (unsigned long long)used, (unsigned long long)size);
    after_block(r);
    return code;
}

/* The line "OFFSETS TYPE" / "CONNECTIVITY TYPE". */
static fc_code array_line(vtk_reader *r, const char *keyword, fc_scalar_type *type, fc_error *err)
{
    fc_span line, word, type_text;
    if (!fc_cursor_next_nonblank_line(r->c, &line) || !fc_span_next_token(&line, &word) ||
        !fc_span_iequals(word, keyword) || !fc_span_next_token(&line, &type_text) || !type_named(type_text, type))
        return fc_cursor_fail(r->c, err, "\"%s TYPE\" expected", keyword);
    return FC_OK;
}

/* 5.1: offsets (cells + 1 of them, from 0 rising to the connectivity's length), then the connectivity. */
static fc_code read_cells_offsets(vtk_reader *r, uint64_t offsets, uint64_t connectivity, bool keep, bool strip,
                                  fc_error *err)
{
    if (offsets == 0 || offsets > (1ull << 26) || connectivity > (1ull << 28))
        return fc_cursor_fail(r->c, err, "%llu offsets and %llu indices are not a cell array this reader takes",
                              (unsigned long long)offsets, (unsigned long long)connectivity);
    fc_scalar_type type;
    fc_code code = array_line(r, "OFFSETS", &type, err);
    uint64_t *starts = code == FC_OK ? malloc(offsets * sizeof *starts) : NULL;
    if (code == FC_OK && !starts)
        code = fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", r->c->name);
    for (uint64_t i = 0; i < offsets && code == FC_OK; i++) {
        code = read_index(r, type, (double)connectivity + 1.0, &starts[i], err);
        if (code == FC_OK && ((i == 0 && starts[0] != 0) || (i > 0 && starts[i] < starts[i - 1]) ||
                              (i > 0 && starts[i] - starts[i - 1] > MAX_CORNERS)))
            code = fc_cursor_fail(r->c, err, "offset %llu does not start a cell after the previous one",
                                  (unsigned long long)i);
    }
    if (code == FC_OK && starts[offsets - 1] != connectivity)
        code = fc_cursor_fail(r->c, err, "the last offset is not the connectivity's length %llu",
                              (unsigned long long)connectivity);
    after_block(r);
    if (code == FC_OK)
        code = array_line(r, "CONNECTIVITY", &type, err);
    for (uint64_t i = 0; i + 1 < offsets && code == FC_OK; i++) {
        uint64_t n = starts[i + 1] - starts[i];
        for (uint64_t j = 0; j < n && code == FC_OK; j++)
            code = read_index(r, type, 4294967296.0, &r->corners[j], err);
        if (code == FC_OK && keep)
            code = add_cell(r, strip, n, err);
    }
    after_block(r);
    free(starts);
    return code;
}

static fc_code read_cells(vtk_reader *r, fc_span keyword, fc_span rest, fc_error *err)
{
    bool polygons = fc_span_iequals(keyword, "POLYGONS"), strips = fc_span_iequals(keyword, "TRIANGLE_STRIPS");
    fc_span a, b2;
    uint64_t first, second;
    if (!fc_span_next_token(&rest, &a) || !fc_span_to_count(a, &first) || !fc_span_next_token(&rest, &b2) ||
        !fc_span_to_count(b2, &second))
        return fc_cursor_fail(r->c, err, "a cell section line that is not \"KEYWORD N SIZE\"");
    /* 5.1 follows the section line with "OFFSETS TYPE" (text even in a binary file). */
    if (fc_cursor_peek_keyword(r->c, "OFFSETS"))
        return read_cells_offsets(r, first, second, polygons || strips, strips, err);
    return read_cells_legacy(r, first, second, polygons || strips, strips, err);
}

static fc_code read_header(vtk_reader *r, fc_error *err)
{
    fc_span line, word;
    if (!fc_cursor_next_line(r->c, &line) || !fc_span_istarts_with(fc_span_trim(line), "# vtk DataFile"))
        return fc_cursor_fail(r->c, err, "not a legacy VTK file (no \"# vtk DataFile Version\" line)");
    if (!fc_cursor_next_line(r->c, &line))
        return fc_cursor_fail(r->c, err, "the file ends after its first line");
    if (!fc_cursor_next_nonblank_line(r->c, &line))
        return fc_cursor_fail(r->c, err, "no ASCII or BINARY line");
    line = fc_span_trim(line);
    if (fc_span_iequals(line, "BINARY"))
        r->binary = true;
    else if (!fc_span_iequals(line, "ASCII"))
        return fc_cursor_fail(r->c, err, "the third line is neither ASCII nor BINARY");
    if (!fc_cursor_next_nonblank_line(r->c, &line) || !fc_span_next_token(&line, &word) ||
        !fc_span_iequals(word, "DATASET") || !fc_span_next_token(&line, &word))
        return fc_cursor_fail(r->c, err, "no DATASET line");
    if (!fc_span_iequals(word, "POLYDATA"))
        return fc_cursor_fail(r->c, err, "a mesh must be DATASET POLYDATA");
    return FC_OK;
}

fc_code fc_read_mesh_vtk(fc_cursor *c, fc_mesh_builder *b, fc_error *err)
{
    vtk_reader r = {.c = c, .b = b, .corners = malloc(MAX_CORNERS * sizeof(uint64_t))};
    if (!r.corners)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", c->name);
    fc_code code = read_header(&r, err);
    fc_span line, keyword;
    bool points = false;
    while (code == FC_OK && fc_cursor_next_nonblank_line(c, &line)) {
        fc_span rest = line;
        if (!fc_span_next_token(&rest, &keyword))
            continue;
        if (fc_span_iequals(keyword, "POINTS")) {
            code = points ? fc_cursor_fail(c, err, "a second POINTS section") : read_points(&r, rest, err);
            points = true;
        } else if (fc_span_iequals(keyword, "POLYGONS") || fc_span_iequals(keyword, "TRIANGLE_STRIPS") ||
                   fc_span_iequals(keyword, "VERTICES") || fc_span_iequals(keyword, "LINES")) {
            code = points ? read_cells(&r, keyword, rest, err) : fc_cursor_fail(c, err, "cells before POINTS");
        } else if (fc_span_iequals(keyword, "POINT_DATA") || fc_span_iequals(keyword, "CELL_DATA") ||
                   fc_span_iequals(keyword, "FIELD")) {
            break;
        } else if (fc_span_iequals(keyword, "METADATA")) {
            /* 5.1's metadata block runs to the next blank line. */
            while (fc_cursor_next_line(c, &line) && !fc_span_is_blank(line))
                ;
        } else {
            char quoted[FC_QUOTE_MAX];
            code = fc_cursor_fail(c, err, "unknown section \"%s\"", fc_span_quote(keyword, quoted, sizeof quoted));
        }
    }
    free(r.corners);
    return code;
}
