/* mesh_stl.c — STL: binary (an 80-byte header, a u32 count T and T records
 * of 50 bytes: normal, three vertices as little-endian f32, a u16) when the
 * size is exactly 84 + 50 T; else ascii ("solid", then "facet normal ...
 * outer loop vertex x y z ... endloop endfacet", "endsolid"). STL stores each
 * triangle's corners, so each triangle brings its own three vertices. */
#include "mesh_formats.h"

#include <string.h>

#include "fc_error.h"

#define HEADER_SIZE 84u
#define RECORD_SIZE 50u
#define MAX_LOOP 64u

static uint32_t load_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static fc_code read_binary(fc_cursor *c, fc_mesh_builder *b, uint32_t triangles, fc_error *err)
{
    c->binary = true;
    fc_code code = fc_mesh_builder_reserve(b, c, 3ull * triangles, triangles, err);
    c->pos = HEADER_SIZE;
    for (uint32_t t = 0; code == FC_OK && t < triangles; t++) {
        c->pos += 12;   /* the facet normal: recomputed from the winding */
        uint64_t corners[3];
        for (int v = 0; v < 3 && code == FC_OK; v++) {
            double xyz[3];
            for (int k = 0; k < 3; k++)
                fc_cursor_read_scalar(c, FC_SCALAR_F32, false, &xyz[k]);   /* the size check proved them there */
            corners[v] = b->mesh.vertex_count;
            code = fc_mesh_builder_vertex(b, c, xyz, err);
        }
        c->pos += 2;    /* attribute byte count */
        if (code == FC_OK)
            code = fc_mesh_builder_polygon(b, c, corners, 3, err);
    }
    return code;
}

/* The next token must be `word`. */
static fc_code expect(fc_cursor *c, const char *word, fc_error *err)
{
    fc_span token;
    char quoted[FC_QUOTE_MAX];
    if (!fc_cursor_next_token(c, &token))
        return fc_cursor_fail(c, err, "the file ends where \"%s\" was expected", word);
    if (!fc_span_iequals(token, word))
        return fc_cursor_fail(c, err, "\"%s\" where \"%s\" was expected", fc_span_quote(token, quoted, sizeof quoted),
                              word);
    return FC_OK;
}

static fc_code read_numbers(fc_cursor *c, double *out, int count, const char *what, fc_error *err)
{
    fc_span token;
    for (int k = 0; k < count; k++)
        if (!fc_cursor_next_token(c, &token) || !fc_span_to_double(token, &out[k]))
            return fc_cursor_fail(c, err, "%s needs %d numbers", what, count);
    return FC_OK;
}

/* "facet normal nx ny nz outer loop (vertex x y z)+ endloop endfacet", after "facet". */
static fc_code read_facet(fc_cursor *c, fc_mesh_builder *b, fc_error *err)
{
    double normal[3];
    fc_code code = expect(c, "normal", err);
    if (code == FC_OK)
        code = read_numbers(c, normal, 3, "a facet normal", err);
    if (code == FC_OK)
        code = expect(c, "outer", err);
    if (code == FC_OK)
        code = expect(c, "loop", err);
    uint64_t corners[MAX_LOOP];
    uint64_t count = 0;
    fc_span token;
    while (code == FC_OK) {
        if (!fc_cursor_next_token(c, &token))
            return fc_cursor_fail(c, err, "the file ends inside a facet");
        if (fc_span_iequals(token, "endloop"))
            break;
        if (!fc_span_iequals(token, "vertex"))
            return fc_cursor_fail(c, err, "a facet's loop holds something other than \"vertex\" lines");
        if (count == MAX_LOOP)
            return fc_cursor_fail(c, err, "a facet of more than %u vertices", MAX_LOOP);
        double xyz[3];
        code = read_numbers(c, xyz, 3, "a vertex", err);
        corners[count++] = b->mesh.vertex_count;
        if (code == FC_OK)
            code = fc_mesh_builder_vertex(b, c, xyz, err);
    }
    if (code == FC_OK)
        code = expect(c, "endfacet", err);
    return code == FC_OK ? fc_mesh_builder_polygon(b, c, corners, count, err) : code;
}

static fc_code read_ascii(fc_cursor *c, fc_mesh_builder *b, fc_error *err)
{
    fc_span line, token;
    if (!fc_cursor_next_nonblank_line(c, &line) || !fc_span_next_token(&line, &token) ||
        !fc_span_iequals(token, "solid"))
        return fc_cursor_fail(c, err, "neither a binary STL (84 + 50 T bytes) nor an ascii one (\"solid\")");
    fc_code code = FC_OK;
    while (code == FC_OK && fc_cursor_next_token(c, &token)) {
        if (fc_span_iequals(token, "facet"))
            code = read_facet(c, b, err);
        else if (fc_span_iequals(token, "endsolid") || fc_span_iequals(token, "solid"))
            fc_cursor_next_line(c, &line);   /* the solid's name, if any; another solid may follow */
        else
            code = fc_cursor_fail(c, err, "\"%s\" where \"facet\" or \"endsolid\" was expected",
                                  fc_span_quote(token, (char[FC_QUOTE_MAX]){0}, FC_QUOTE_MAX));
    }
    return code;
}

fc_code fc_read_mesh_stl(fc_cursor *c, fc_mesh_builder *b, fc_error *err)
{
    if (c->size >= HEADER_SIZE) {
        uint32_t triangles = load_u32(c->data + 80);
        if ((uint64_t)HEADER_SIZE + (uint64_t)RECORD_SIZE * triangles == c->size)
            return read_binary(c, b, triangles, err);
    }
    /* Binary headers may start with "solid" too (some writers put it there),
     * but text has no NUL byte: ascii is "solid" and no NUL in the first 512 bytes. */
    size_t head = c->size < 512 ? c->size : 512;
    bool ascii_start = fc_cursor_peek_keyword(c, "solid") && memchr(c->data, 0, head) == NULL;
    if (!ascii_start && c->size >= HEADER_SIZE) {
        c->binary = true;
        return fc_cursor_fail(c, err, "a binary STL of %u triangles needs %llu bytes, the file has %zu",
                              (unsigned)load_u32(c->data + 80),
                              (unsigned long long)HEADER_SIZE + (unsigned long long)RECORD_SIZE * load_u32(c->data + 80),
                              c->size);
    }
    return read_ascii(c, b, err);
}
