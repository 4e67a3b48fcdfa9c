/* wire_mesh.c — MESH and MESH_TRANSFORM (wire_mesh.h, PROTOCOL.md section 12). */
#include "wire_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "wire_io.h"

void fc_mesh_identity(float transform[12])
{
    static const float identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    memcpy(transform, identity, sizeof identity);
}

static bool all_finite(const float *v, size_t count)
{
    for (size_t i = 0; i < count; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

static fc_code check_counts(const fc_mesh *m, fc_error *err)
{
    if (m->vertex_count > FC_MESH_MAX_VERTICES || m->triangle_count > FC_MESH_MAX_TRIANGLES)
        return fc_error_set(err, FC_ERR_LIMIT, "MESH %u: %u vertices and %u triangles exceed the limits of %u and %u",
                            (unsigned)m->id, (unsigned)m->vertex_count, (unsigned)m->triangle_count,
                            FC_MESH_MAX_VERTICES, FC_MESH_MAX_TRIANGLES);
    if (m->triangle_count == 0 && m->vertex_count != 0)
        return fc_error_set(err, FC_ERR_INVALID_VALUE,
                            "MESH %u: %u vertices but no triangles (a removal has neither)", (unsigned)m->id,
                            (unsigned)m->vertex_count);
    return FC_OK;
}

static fc_code check_look(const fc_mesh *m, fc_error *err)
{
    for (int k = 0; k < 3; k++)
        if (!(m->color[k] >= 0.0f && m->color[k] <= 1.0f))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "MESH %u: color component %d is %g, not in [0, 1]",
                                (unsigned)m->id, k, (double)m->color[k]);
    if (!(m->opacity >= 0.0f && m->opacity <= 1.0f))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "MESH %u: opacity %g is not in [0, 1]", (unsigned)m->id,
                            (double)m->opacity);
    if (!all_finite(m->transform, 12))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "MESH %u: the transform is not finite", (unsigned)m->id);
    return FC_OK;
}

/* The first vertex (or normal) that is not finite, as a message. */
static fc_code check_points(const fc_mesh *m, const float *v, const char *what, fc_error *err)
{
    for (uint32_t i = 0; v && i < m->vertex_count; i++)
        if (!all_finite(v + 3 * (size_t)i, 3))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "MESH %u: %s %u is (%g, %g, %g), not finite",
                                (unsigned)m->id, what, (unsigned)i, (double)v[3 * (size_t)i],
                                (double)v[3 * (size_t)i + 1], (double)v[3 * (size_t)i + 2]);
    return FC_OK;
}

static fc_code check_indices(const fc_mesh *m, fc_error *err)
{
    for (uint32_t t = 0; t < m->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t index = m->indices[3 * (size_t)t + k];
            if (index >= m->vertex_count)
                return fc_error_set(err, FC_ERR_INVALID_VALUE,
                                    "MESH %u: triangle %u refers to vertex %u, but the mesh has %u vertices",
                                    (unsigned)m->id, (unsigned)t, (unsigned)index, (unsigned)m->vertex_count);
        }
    return FC_OK;
}

fc_code fc_mesh_validate(const fc_mesh *m, fc_error *err)
{
    fc_code code = check_counts(m, err);
    if (code == FC_OK)
        code = check_look(m, err);
    if (code == FC_OK && m->triangle_count > 0 && (!m->vertices || !m->indices))
        code = fc_error_set(err, FC_ERR_USAGE, "MESH %u: %u triangles without vertex or index arrays",
                            (unsigned)m->id, (unsigned)m->triangle_count);
    if (code == FC_OK)
        code = check_points(m, m->vertices, "vertex", err);
    if (code == FC_OK)
        code = check_points(m, m->normals, "normal", err);
    if (code == FC_OK)
        code = check_indices(m, err);
    return code;
}

/* Payload bytes after the fixed part: vertices, indices, normals. Counts are
 * within the limits, so this is below 2^32 * 36 and fits u64. */
static uint64_t array_bytes(uint32_t vertices, uint32_t triangles, bool normals)
{
    return 12u * (uint64_t)vertices * (normals ? 2u : 1u) + 12u * (uint64_t)triangles;
}

static void put_fixed(fc_buf *out, const fc_mesh *m, uint32_t wire_flags)
{
    wire_put_u32(out, m->id);
    wire_put_u32(out, wire_flags);
    wire_put_u32(out, m->vertex_count);
    wire_put_u32(out, m->triangle_count);
    wire_put_f32_array(out, m->color, 3);
    wire_put_f32(out, m->opacity);
    wire_put_f32_array(out, m->transform, 12);
}

fc_code fc_wire_write_mesh(fc_buf *out, uint32_t request_id, const fc_mesh *m, fc_error *err)
{
    if (m->flags & ~(uint32_t)FC_MESH_HIDE_NEAR)
        return fc_error_set(err, FC_ERR_USAGE, "MESH %u: unknown flags 0x%x", (unsigned)m->id, (unsigned)m->flags);
    fc_code code = fc_mesh_validate(m, err);
    bool normals = m->normals != NULL && m->vertex_count > 0;
    uint64_t arrays = array_bytes(m->vertex_count, m->triangle_count, normals);
    if (code == FC_OK)
        code = wire_check_length(FC_MESH_FIXED_SIZE, arrays, 1, "MESH", err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, FC_MSG_MESH, request_id,
                                      (uint32_t)(FC_MESH_FIXED_SIZE + arrays));
    fc_buf_reserve(out, (size_t)arrays);
    put_fixed(out, m, m->flags | (normals ? FC_MESH_WIRE_NORMALS : 0u));
    wire_put_f32_array(out, m->vertices, 3 * (size_t)m->vertex_count);
    wire_put_u32_array(out, m->indices, 3 * (size_t)m->triangle_count);
    if (normals)
        wire_put_f32_array(out, m->normals, 3 * (size_t)m->vertex_count);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_write_mesh_removal(fc_buf *out, uint32_t request_id, uint32_t id, fc_error *err)
{
    fc_mesh m = {.id = id, .color = {1, 1, 1}, .opacity = 1};
    fc_mesh_identity(m.transform);
    return fc_wire_write_mesh(out, request_id, &m, err);
}

/* Fixed fields in wire order; the layout checks of 12.1 steps 1-3. */
static void read_fixed(wire_reader *r, fc_mesh *m, uint32_t *wire_flags)
{
    m->id = wire_get_u32(r, "id");
    *wire_flags = wire_get_u32(r, "flags");
    m->vertex_count = wire_get_u32(r, "vertex_count");
    m->triangle_count = wire_get_u32(r, "triangle_count");
    wire_get_f32_array(r, m->color, 3, "color");
    m->opacity = wire_get_f32(r, "opacity");
    wire_get_f32_array(r, m->transform, 12, "transform");
    if (r->code != FC_OK)
        return;
    m->flags = *wire_flags & FC_MESH_HIDE_NEAR;
    if (*wire_flags & ~(uint32_t)FC_MESH_WIRE_FLAGS)
        wire_fail(r, FC_ERR_MALFORMED, "unknown flag bits 0x%x", *wire_flags & ~(uint32_t)FC_MESH_WIRE_FLAGS);
    else if (m->vertex_count > FC_MESH_MAX_VERTICES || m->triangle_count > FC_MESH_MAX_TRIANGLES)
        wire_fail(r, FC_ERR_LIMIT, "%u vertices and %u triangles exceed the limits of %u and %u",
                  (unsigned)m->vertex_count, (unsigned)m->triangle_count, FC_MESH_MAX_VERTICES, FC_MESH_MAX_TRIANGLES);
    else if (array_bytes(m->vertex_count, m->triangle_count, *wire_flags & FC_MESH_WIRE_NORMALS) != wire_remaining(r))
        wire_fail(r, FC_ERR_MALFORMED, "%u vertices and %u triangles%s do not match the %zu bytes that follow",
                  (unsigned)m->vertex_count, (unsigned)m->triangle_count,
                  (*wire_flags & FC_MESH_WIRE_NORMALS) ? " with normals" : "", wire_remaining(r));
}

/* The arrays, copied into one block the mesh points into. */
static fc_code read_arrays(wire_reader *r, fc_mesh *m, bool normals, void **storage, fc_error *err)
{
    size_t bytes = (size_t)array_bytes(m->vertex_count, m->triangle_count, normals);
    uint8_t *block = malloc(bytes ? bytes : 1);
    if (!block)
        return fc_error_set(err, FC_ERR_NOMEM, "MESH %u: no memory for %zu bytes of arrays", (unsigned)m->id, bytes);
    size_t v3 = 3 * (size_t)m->vertex_count, t3 = 3 * (size_t)m->triangle_count;
    float *vertices = (float *)block;
    uint32_t *indices = (uint32_t *)(block + 4 * v3);
    float *normal_array = normals ? (float *)(block + 4 * (v3 + t3)) : NULL;
    wire_get_f32_array(r, vertices, v3, "vertices");
    wire_get_u32_array(r, indices, t3, "indices");
    if (normal_array)
        wire_get_f32_array(r, normal_array, v3, "normals");
    wire_expect_end(r);
    if (r->code != FC_OK) {
        free(block);
        return r->code;
    }
    m->vertices = vertices;
    m->indices = indices;
    m->normals = normal_array;
    *storage = block;
    return FC_OK;
}

fc_code fc_wire_read_mesh(const uint8_t *p, size_t n, fc_mesh *out, void **storage, fc_error *err)
{
    *storage = NULL;
    wire_reader r = wire_reader_start(p, n, "MESH", err);
    fc_mesh m = {0};
    uint32_t wire_flags = 0;
    read_fixed(&r, &m, &wire_flags);
    if (r.code != FC_OK)
        return r.code;
    fc_code code = check_counts(&m, err);
    if (code == FC_OK)
        code = check_look(&m, err);
    if (code != FC_OK)
        return code;
    void *block = NULL;
    if (m.triangle_count > 0) {
        code = read_arrays(&r, &m, wire_flags & FC_MESH_WIRE_NORMALS, &block, err);
        if (code == FC_OK)
            code = fc_mesh_validate(&m, err);
        if (code != FC_OK) {
            free(block);
            return code;
        }
    }
    *out = m;
    *storage = block;
    return FC_OK;
}

/* Entries' transforms finite and ids distinct (quadratic: at most 64 entries). */
static fc_code check_transforms(const fc_mesh_transform *e, uint32_t count, fc_error *err)
{
    for (uint32_t i = 0; i < count; i++) {
        if (!all_finite(e[i].transform, 12))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "MESH_TRANSFORM: entry %u (mesh %u) is not finite",
                                (unsigned)i, (unsigned)e[i].id);
        for (uint32_t j = 0; j < i; j++)
            if (e[j].id == e[i].id)
                return fc_error_set(err, FC_ERR_INVALID_VALUE, "MESH_TRANSFORM: mesh %u appears in entries %u and %u",
                                    (unsigned)e[i].id, (unsigned)j, (unsigned)i);
    }
    return FC_OK;
}

fc_code fc_wire_write_mesh_transforms(fc_buf *out, uint32_t request_id, const fc_mesh_transform *entries,
                                      uint32_t count, fc_error *err)
{
    if (count > FC_MESH_MAX_COUNT)
        return fc_error_set(err, FC_ERR_LIMIT, "MESH_TRANSFORM: %u entries exceed the limit of %u", (unsigned)count,
                            FC_MESH_MAX_COUNT);
    if (count > 0 && !entries)
        return fc_error_set(err, FC_ERR_USAGE, "MESH_TRANSFORM: %u entries without an array", (unsigned)count);
    fc_code code = check_transforms(entries, count, err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, FC_MSG_MESH_TRANSFORM, request_id,
                                      4u + FC_MESH_TRANSFORM_ENTRY_SIZE * count);
    wire_put_u32(out, count);
    for (uint32_t i = 0; i < count; i++) {
        wire_put_u32(out, entries[i].id);
        wire_put_f32_array(out, entries[i].transform, 12);
    }
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_mesh_transforms(const uint8_t *p, size_t n, fc_mesh_transform entries[FC_MESH_MAX_COUNT],
                                     uint32_t *count, fc_error *err)
{
    wire_reader r = wire_reader_start(p, n, "MESH_TRANSFORM", err);
    uint32_t k = wire_get_u32(&r, "count");
    if (r.code == FC_OK && k > FC_MESH_MAX_COUNT)
        wire_fail(&r, FC_ERR_LIMIT, "%u entries exceed the limit of %u", (unsigned)k, FC_MESH_MAX_COUNT);
    else if (r.code == FC_OK && (uint64_t)k * FC_MESH_TRANSFORM_ENTRY_SIZE != wire_remaining(&r))
        wire_fail(&r, FC_ERR_MALFORMED, "%u entries of %u bytes do not match the %zu bytes that follow", (unsigned)k,
                  FC_MESH_TRANSFORM_ENTRY_SIZE, wire_remaining(&r));
    fc_mesh_transform read[FC_MESH_MAX_COUNT];
    for (uint32_t i = 0; r.code == FC_OK && i < k; i++) {
        read[i].id = wire_get_u32(&r, "id");
        wire_get_f32_array(&r, read[i].transform, 12, "transform");
    }
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    fc_code code = check_transforms(read, k, err);
    if (code != FC_OK)
        return code;
    memcpy(entries, read, k * sizeof *read);
    *count = k;
    return FC_OK;
}
