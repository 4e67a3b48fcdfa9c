/* wire_surface.c — SURFACE and SURFACE_PART (wire_surface.h, PROTOCOL.md 13):
 * the request, a mesh's body cut into parts, and their assembly. */
#include "wire_surface.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "wire_io.h"

#define BODY_ARRAYS 7   /* positions, normals, indices, speed, density, velocity, id */

/* One array of the body: where it lies in a mesh, and its 32-bit words. */
typedef struct body_array {
    void *data;
    uint64_t words;
} body_array;

/* The arrays of a body in wire order, those absent with 0 words. */
static void body_layout(uint32_t v, uint32_t t, uint32_t attributes, body_array out[BODY_ARRAYS])
{
    const uint64_t words[BODY_ARRAYS] = {
        3ull * v, 3ull * v, 3ull * t,
        (attributes & FC_SURFACE_SPEED) ? v : 0, (attributes & FC_SURFACE_DENSITY) ? v : 0,
        (attributes & FC_SURFACE_VELOCITY) ? 3ull * v : 0, (attributes & FC_SURFACE_ID) ? v : 0};
    for (int i = 0; i < BODY_ARRAYS; i++)
        out[i] = (body_array){NULL, words[i]};
}

/* The same, pointing at a mesh's arrays. */
static void mesh_layout(const fc_surface_mesh *m, body_array out[BODY_ARRAYS])
{
    body_layout(m->vertex_count, m->triangle_count, m->attributes, out);
    void *data[BODY_ARRAYS] = {m->positions, m->normals, m->indices, m->speed, m->density, m->velocity, m->id};
    for (int i = 0; i < BODY_ARRAYS; i++)
        out[i].data = data[i];
}

uint64_t fc_surface_body_size(uint32_t vertex_count, uint32_t triangle_count, uint32_t attributes)
{
    body_array arrays[BODY_ARRAYS];
    body_layout(vertex_count, triangle_count, attributes, arrays);
    uint64_t words = 0;
    for (int i = 0; i < BODY_ARRAYS; i++)
        words += arrays[i].words;
    return 4 * words;
}

uint32_t fc_surface_part_count(uint64_t body_size)
{
    uint64_t parts = (body_size + FC_SURFACE_PART_DATA_MAX - 1) / FC_SURFACE_PART_DATA_MAX;
    return parts ? (uint32_t)parts : 1u;
}

static bool all_finite(const float *v, uint64_t count, uint64_t *bad)
{
    for (uint64_t i = 0; i < count; i++)
        if (!isfinite(v[i])) {
            *bad = i;
            return false;
        }
    return true;
}

/* INVALID_VALUE naming the vertex of the first non-finite value of `name`. */
static fc_code check_finite(const float *v, uint32_t vertex_count, unsigned per_vertex, const char *name,
                            fc_error *err)
{
    uint64_t bad = 0;
    if (v && !all_finite(v, (uint64_t)vertex_count * per_vertex, &bad))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "surface mesh: %s of vertex %llu is not finite", name,
                            (unsigned long long)(bad / per_vertex));
    return FC_OK;
}

static fc_code check_counts(const fc_surface_mesh *m, fc_error *err)
{
    if (m->vertex_count > FC_SURFACE_MAX_VERTICES)
        return fc_error_set(err, FC_ERR_LIMIT, "surface mesh: %u vertices, more than the %u allowed",
                            (unsigned)m->vertex_count, (unsigned)FC_SURFACE_MAX_VERTICES);
    if (m->triangle_count > FC_SURFACE_MAX_TRIANGLES)
        return fc_error_set(err, FC_ERR_LIMIT, "surface mesh: %u triangles, more than the %u allowed",
                            (unsigned)m->triangle_count, (unsigned)FC_SURFACE_MAX_TRIANGLES);
    if ((m->vertex_count == 0) != (m->triangle_count == 0))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "surface mesh: %u vertices but %u triangles",
                            (unsigned)m->vertex_count, (unsigned)m->triangle_count);
    if (m->attributes & ~FC_SURFACE_ATTRIBUTES_ALL)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "surface mesh: unknown attribute bits 0x%x",
                            (unsigned)(m->attributes & ~FC_SURFACE_ATTRIBUTES_ALL));
    return FC_OK;
}

static fc_code check_arrays_present(const fc_surface_mesh *m, fc_error *err)
{
    body_array arrays[BODY_ARRAYS];
    mesh_layout(m, arrays);
    static const char *const names[BODY_ARRAYS] = {"positions", "normals", "indices", "speed",
                                                   "density", "velocity", "id"};
    for (int i = 0; i < BODY_ARRAYS; i++)
        if (arrays[i].words > 0 && !arrays[i].data)
            return fc_error_set(err, FC_ERR_USAGE, "surface mesh: %s announced but missing", names[i]);
    return FC_OK;
}

static fc_code check_indices(const fc_surface_mesh *m, fc_error *err)
{
    for (uint64_t i = 0; i < 3ull * m->triangle_count; i++)
        if (m->indices[i] >= m->vertex_count)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "surface mesh: triangle %llu uses vertex %u of %u",
                                (unsigned long long)(i / 3), (unsigned)m->indices[i], (unsigned)m->vertex_count);
    return FC_OK;
}

fc_code fc_surface_mesh_validate(const fc_surface_mesh *m, fc_error *err)
{
    fc_code code = check_counts(m, err);
    if (code == FC_OK)
        code = check_arrays_present(m, err);
    if (code == FC_OK)
        code = check_finite(m->positions, m->vertex_count, 3, "position", err);
    if (code == FC_OK)
        code = check_finite(m->normals, m->vertex_count, 3, "normal", err);
    if (code == FC_OK)
        code = check_finite(m->speed, m->vertex_count, 1, "speed", err);
    if (code == FC_OK)
        code = check_finite(m->density, m->vertex_count, 1, "density", err);
    if (code == FC_OK)
        code = check_finite(m->velocity, m->vertex_count, 3, "velocity", err);
    if (code == FC_OK)
        code = check_indices(m, err);
    return code;
}

fc_code fc_wire_write_surface_request(fc_buf *out, uint32_t request_id, uint32_t attributes, fc_error *err)
{
    if (attributes & ~FC_SURFACE_ATTRIBUTES_ALL)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "SURFACE: unknown attribute bits 0x%x",
                            (unsigned)(attributes & ~FC_SURFACE_ATTRIBUTES_ALL));
    size_t start = wire_begin_message(out, FC_MSG_SURFACE, request_id, FC_SURFACE_REQUEST_SIZE);
    wire_put_u32(out, attributes);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_surface_request(const uint8_t *p, size_t n, uint32_t *attributes, fc_error *err)
{
    wire_reader r = wire_reader_start(p, n, "SURFACE", err);
    uint32_t bits = wire_get_u32(&r, "attributes");
    wire_expect_end(&r);
    if (r.code == FC_OK && (bits & ~FC_SURFACE_ATTRIBUTES_ALL))
        wire_fail(&r, FC_ERR_INVALID_VALUE, "unknown attribute bits 0x%x", (unsigned)(bits & ~FC_SURFACE_ATTRIBUTES_ALL));
    if (r.code == FC_OK)
        *attributes = bits;
    return r.code;
}

/* Appends the words of the body in [offset, offset + size) (both multiples of 4). */
static void put_body_range(fc_buf *out, const body_array arrays[BODY_ARRAYS], uint64_t offset, uint64_t size)
{
    uint64_t first = offset / 4, end = (offset + size) / 4, at = 0;
    for (int i = 0; i < BODY_ARRAYS && at < end; i++) {
        uint64_t from = first > at ? first - at : 0;
        uint64_t to = end - at < arrays[i].words ? end - at : arrays[i].words;
        if (from < to) {
            const uint32_t *words = (const uint32_t *)arrays[i].data + from;
            if (WIRE_HOST_IS_LITTLE_ENDIAN)
                wire_put_bytes(out, words, (size_t)(4 * (to - from)));
            else
                wire_put_u32_array(out, words, (size_t)(to - from));
        }
        at += arrays[i].words;
    }
}

fc_code fc_wire_write_surface_part(fc_buf *out, uint32_t request_id, const fc_surface_mesh *mesh, float extract_ms,
                                   uint32_t index, fc_error *err)
{
    fc_code code = fc_surface_mesh_validate(mesh, err);
    if (code != FC_OK)
        return code;
    uint64_t body = fc_surface_body_size(mesh->vertex_count, mesh->triangle_count, mesh->attributes);
    uint32_t parts = fc_surface_part_count(body);
    if (index >= parts)
        return fc_error_set(err, FC_ERR_USAGE, "SURFACE_PART: part %u of %u", (unsigned)index, (unsigned)parts);
    uint64_t offset = (uint64_t)index * FC_SURFACE_PART_DATA_MAX;
    uint64_t size = body - offset < FC_SURFACE_PART_DATA_MAX ? body - offset : FC_SURFACE_PART_DATA_MAX;
    size_t start = wire_begin_message(out, FC_MSG_SURFACE_PART, request_id,
                                      (uint32_t)(FC_SURFACE_PART_FIXED_SIZE + size));
    wire_put_u32(out, index);
    wire_put_u32(out, parts);
    wire_put_u32(out, mesh->vertex_count);
    wire_put_u32(out, mesh->triangle_count);
    wire_put_u32(out, mesh->attributes);
    wire_put_f32(out, extract_ms);
    wire_put_u64(out, offset);
    wire_put_u32(out, (uint32_t)size);
    body_array arrays[BODY_ARRAYS];
    mesh_layout(mesh, arrays);
    put_body_range(out, arrays, offset, size);
    return wire_end_message(out, start, err);
}

void fc_surface_assembly_init(fc_surface_assembly *a, uint64_t max_body)
{
    memset(a, 0, sizeof *a);
    a->max_body = max_body ? max_body
                           : fc_surface_body_size(FC_SURFACE_MAX_VERTICES, FC_SURFACE_MAX_TRIANGLES,
                                                  FC_SURFACE_ATTRIBUTES_ALL);
}

void fc_surface_assembly_free(fc_surface_assembly *a)
{
    free(a->body);
    uint64_t max_body = a->max_body;
    memset(a, 0, sizeof *a);
    a->max_body = max_body;
}

/* The fixed fields of one part. */
typedef struct part_fields {
    uint32_t index, count, vertex_count, triangle_count, attributes;
    float extract_ms;
    uint64_t offset;
    uint32_t size;
} part_fields;

/* Checks the first part's announcement: the reply's counts and the K they imply. */
static void check_first_part(wire_reader *r, const part_fields *f, uint64_t max_body)
{
    fc_surface_mesh counts = {.vertex_count = f->vertex_count, .triangle_count = f->triangle_count,
                              .attributes = f->attributes};
    fc_error why = {FC_OK, ""};
    if (check_counts(&counts, &why) != FC_OK) {
        wire_fail(r, why.code, "%s", why.message);
        return;
    }
    uint64_t body = fc_surface_body_size(f->vertex_count, f->triangle_count, f->attributes);
    if (body > max_body)
        wire_fail(r, FC_ERR_LIMIT, "a body of %llu bytes, more than the %llu this receiver takes",
                  (unsigned long long)body, (unsigned long long)max_body);
    else if (f->count != fc_surface_part_count(body))
        wire_fail(r, FC_ERR_MALFORMED, "%u parts announced for a body of %llu bytes (%u parts)", (unsigned)f->count,
                  (unsigned long long)body, (unsigned)fc_surface_part_count(body));
}

/* Checks a part against the reply so far (the first part against itself). */
static void check_part(wire_reader *r, const fc_surface_assembly *a, const part_fields *f)
{
    if (f->index != a->next_index) {
        wire_fail(r, FC_ERR_MALFORMED, "part %u arrived where part %u was due", (unsigned)f->index,
                  (unsigned)a->next_index);
        return;
    }
    if (f->index > 0 && (f->count != a->part_count || f->vertex_count != a->vertex_count ||
                         f->triangle_count != a->triangle_count || f->attributes != a->attributes)) {
        wire_fail(r, FC_ERR_INCONSISTENT, "part %u announces %u parts, %u vertices, %u triangles, attributes 0x%x; "
                  "part 0 announced %u, %u, %u, 0x%x", (unsigned)f->index, (unsigned)f->count,
                  (unsigned)f->vertex_count, (unsigned)f->triangle_count, (unsigned)f->attributes,
                  (unsigned)a->part_count, (unsigned)a->vertex_count, (unsigned)a->triangle_count,
                  (unsigned)a->attributes);
        return;
    }
    uint64_t body = fc_surface_body_size(f->vertex_count, f->triangle_count, f->attributes);
    uint64_t offset = (uint64_t)f->index * FC_SURFACE_PART_DATA_MAX;
    uint64_t size = body - offset < FC_SURFACE_PART_DATA_MAX ? body - offset : FC_SURFACE_PART_DATA_MAX;
    if (f->offset != offset || f->size != size)
        wire_fail(r, FC_ERR_MALFORMED, "part %u holds bytes %llu..+%u of the body, not %llu..+%llu",
                  (unsigned)f->index, (unsigned long long)f->offset, (unsigned)f->size, (unsigned long long)offset,
                  (unsigned long long)size);
    else if (wire_remaining(r) != f->size)
        wire_fail(r, FC_ERR_MALFORMED, "part %u announces %u data bytes, %zu follow", (unsigned)f->index,
                  (unsigned)f->size, wire_remaining(r));
}

static part_fields read_part_fields(wire_reader *r)
{
    part_fields f;
    f.index = wire_get_u32(r, "index");
    f.count = wire_get_u32(r, "count");
    f.vertex_count = wire_get_u32(r, "vertex_count");
    f.triangle_count = wire_get_u32(r, "triangle_count");
    f.attributes = wire_get_u32(r, "attributes");
    f.extract_ms = wire_get_f32(r, "extract_ms");
    f.offset = wire_get_u64(r, "offset");
    f.size = wire_get_u32(r, "size");
    return f;
}

static void take_part_data(wire_reader *r, fc_surface_assembly *a, const part_fields *f)
{
    const uint8_t *data = wire_get_bytes(r, f->size, "data");
    if (r->code != FC_OK)
        return;
    uint8_t *grown = realloc(a->body, a->received + f->size + 1);
    if (!grown) {
        wire_fail(r, FC_ERR_NOMEM, "no memory for part %u (%u bytes)", (unsigned)f->index, (unsigned)f->size);
        return;
    }
    a->body = grown;
    memcpy(a->body + a->received, data, f->size);
    a->received += f->size;
}

fc_code fc_surface_assembly_add(fc_surface_assembly *a, const uint8_t *p, size_t n, bool *complete, fc_error *err)
{
    *complete = false;
    wire_reader r = wire_reader_start(p, n, "SURFACE_PART", err);
    part_fields f = read_part_fields(&r);
    if (r.code == FC_OK && a->next_index >= a->part_count && a->next_index > 0)
        wire_fail(&r, FC_ERR_MALFORMED, "a part after the reply's last (%u of %u)", (unsigned)f.index,
                  (unsigned)a->part_count);
    if (r.code == FC_OK && f.index == 0 && a->next_index == 0)
        check_first_part(&r, &f, a->max_body);
    if (r.code == FC_OK)
        check_part(&r, a, &f);
    if (r.code == FC_OK) {
        if (f.index == 0) {
            a->part_count = f.count;
            a->vertex_count = f.vertex_count;
            a->triangle_count = f.triangle_count;
            a->attributes = f.attributes;
            a->extract_ms = f.extract_ms;
            a->body_size = fc_surface_body_size(f.vertex_count, f.triangle_count, f.attributes);
        }
        take_part_data(&r, a, &f);
    }
    if (r.code != FC_OK) {
        a->next_index = UINT32_MAX;   /* failed: no later part is taken */
        a->part_count = 0;
        return r.code;
    }
    a->next_index++;
    *complete = a->next_index == a->part_count;
    return FC_OK;
}

/* Copies `words` 32-bit words of the body at *at into a new array in host order. */
static fc_code take_array(const uint8_t *body, uint64_t *at, uint64_t words, void **out, fc_error *err)
{
    *out = NULL;
    if (words == 0)
        return FC_OK;
    uint8_t *array = malloc((size_t)(4 * words));
    if (!array)
        return fc_error_set(err, FC_ERR_NOMEM, "SURFACE_PART: no memory for an array of %llu words",
                            (unsigned long long)words);
    memcpy(array, body + *at, (size_t)(4 * words));
    wire_words_to_host(array, (size_t)words);
    *at += 4 * words;
    *out = array;
    return FC_OK;
}

fc_code fc_surface_assembly_finish(fc_surface_assembly *a, fc_surface_mesh *out, float *extract_ms, fc_error *err)
{
    memset(out, 0, sizeof *out);
    if (a->part_count == 0 || a->next_index != a->part_count || a->received != a->body_size)
        return fc_error_set(err, FC_ERR_USAGE, "SURFACE_PART: the reply is not complete (%u of %u parts)",
                            (unsigned)a->next_index, (unsigned)a->part_count);
    fc_surface_mesh m = {.vertex_count = a->vertex_count, .triangle_count = a->triangle_count,
                         .attributes = a->attributes};
    body_array arrays[BODY_ARRAYS];
    body_layout(m.vertex_count, m.triangle_count, m.attributes, arrays);
    void **targets[BODY_ARRAYS] = {(void **)&m.positions, (void **)&m.normals, (void **)&m.indices,
                                   (void **)&m.speed, (void **)&m.density, (void **)&m.velocity, (void **)&m.id};
    uint64_t at = 0;
    fc_code code = FC_OK;
    for (int i = 0; i < BODY_ARRAYS && code == FC_OK; i++)
        code = take_array(a->body, &at, arrays[i].words, targets[i], err);
    if (code == FC_OK)
        code = fc_surface_mesh_validate(&m, err);
    if (code != FC_OK) {
        fc_surface_mesh_free(&m);
        return code;
    }
    if (extract_ms)
        *extract_ms = a->extract_ms;
    *out = m;
    fc_surface_assembly_free(a);
    return FC_OK;
}
