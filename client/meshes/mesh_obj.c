/* mesh_obj.c — Wavefront OBJ: "v x y z [w]" vertices and "f" faces whose
 * corners are "i", "i/t", "i//n" or "i/t/n" (only i matters), 1-based, or
 * negative counting back from the last vertex read so far. Polygons are
 * fanned into triangles; every other statement (vn, vt, g, o, s, usemtl,
 * mtllib, l, p, comments) is skipped. */
#include "mesh_formats.h"

#include <stdlib.h>

#include "fc_error.h"

#define MAX_CORNERS 4096u

/* The vertex index of one corner token, made 0-based and absolute. */
static fc_code corner_index(const fc_cursor *c, fc_span token, uint32_t vertex_count, uint64_t *out, fc_error *err)
{
    fc_span rest = token, number;
    fc_span_next_field(&rest, '/', &number);
    bool negative = number.len > 0 && number.ptr[0] == '-';
    fc_span digits = negative ? (fc_span){number.ptr + 1, number.len - 1} : number;
    uint64_t n;
    char quoted[FC_QUOTE_MAX];
    if (!fc_span_to_count(digits, &n) || n == 0)
        return fc_cursor_fail(c, err, "face corner \"%s\" is not a vertex index (1-based, or negative)",
                              fc_span_quote(token, quoted, sizeof quoted));
    if (negative) {
        if (n > vertex_count)
            return fc_cursor_fail(c, err, "face corner %s counts back past the first vertex (%u so far)",
                                  fc_span_quote(token, quoted, sizeof quoted), (unsigned)vertex_count);
        *out = vertex_count - n;
    } else {
        *out = n - 1;
    }
    return FC_OK;
}

static fc_code read_vertex(const fc_cursor *c, fc_mesh_builder *b, fc_span rest, fc_error *err)
{
    double xyz[3];
    fc_span token;
    for (int k = 0; k < 3; k++) {
        if (!fc_span_next_token(&rest, &token) || !fc_span_to_double(token, &xyz[k]))
            return fc_cursor_fail(c, err, "a \"v\" line needs three numbers");
    }
    return fc_mesh_builder_vertex(b, c, xyz, err);
}

static fc_code read_face(const fc_cursor *c, fc_mesh_builder *b, fc_span rest, uint64_t *corners, fc_error *err)
{
    uint64_t count = 0;
    fc_span token;
    while (fc_span_next_token(&rest, &token)) {
        if (count == MAX_CORNERS)
            return fc_cursor_fail(c, err, "a face of more than %u corners", MAX_CORNERS);
        fc_code code = corner_index(c, token, b->mesh.vertex_count, &corners[count++], err);
        if (code != FC_OK)
            return code;
    }
    return fc_mesh_builder_polygon(b, c, corners, count, err);
}

fc_code fc_read_mesh_obj(fc_cursor *c, fc_mesh_builder *b, fc_error *err)
{
    uint64_t *corners = malloc(MAX_CORNERS * sizeof *corners);
    if (!corners)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", c->name);
    fc_code code = FC_OK;
    fc_span line;
    while (code == FC_OK && fc_cursor_next_line(c, &line)) {
        fc_span rest = line, keyword;
        if (!fc_span_next_token(&rest, &keyword))
            continue;
        if (fc_span_iequals(keyword, "v"))
            code = read_vertex(c, b, rest, err);
        else if (fc_span_iequals(keyword, "f"))
            code = read_face(c, b, rest, corners, err);
    }
    free(corners);
    return code;
}
