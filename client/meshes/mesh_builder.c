/* mesh_builder.c — see mesh_builder.h; also fc_mesh_data_free (mesh_reader.h):
 * the arrays are grown here, so they are freed here too. */
#include "mesh_builder.h"

#include <math.h>
#include <stdlib.h>

#include "fc_error.h"

#define MAX_COUNT (1u << 24)   /* FC_MESH_MAX_VERTICES, FC_MESH_MAX_TRIANGLES (wire_mesh.h) */
#define FIRST_CAPACITY 1024u

/* Grows *array of `*capacity` items of `item` bytes to hold `needed`. */
static bool grow(void **array, uint32_t *capacity, uint64_t needed, size_t item)
{
    if (needed <= *capacity)
        return true;
    uint64_t want = *capacity ? *capacity : FIRST_CAPACITY;
    while (want < needed)
        want *= 2;
    if (want > MAX_COUNT)
        want = MAX_COUNT;
    void *grown = realloc(*array, (size_t)want * item);
    if (!grown)
        return false;
    *array = grown;
    *capacity = (uint32_t)want;
    return true;
}

fc_code fc_mesh_builder_reserve(fc_mesh_builder *b, const fc_cursor *c, uint64_t vertices, uint64_t triangles,
                                fc_error *err)
{
    (void)b;
    if (vertices > MAX_COUNT || triangles > MAX_COUNT)
        return fc_error_set(err, FC_ERR_LIMIT, "%s: %llu vertices and %llu triangles exceed the limit of %u", c->name,
                            (unsigned long long)vertices, (unsigned long long)triangles, MAX_COUNT);
    return FC_OK;   /* grown as the data comes: a header's count is not trusted with memory */
}

fc_code fc_mesh_builder_vertex(fc_mesh_builder *b, const fc_cursor *c, const double xyz[3], fc_error *err)
{
    fc_mesh_data *m = &b->mesh;
    for (int k = 0; k < 3; k++)
        if (!isfinite(xyz[k]) || fabs(xyz[k]) > 3.0e38)
            return fc_cursor_fail(c, err, "vertex %u has a coordinate that is not a finite float",
                                  (unsigned)m->vertex_count);
    if (m->vertex_count >= MAX_COUNT)
        return fc_error_set(err, FC_ERR_LIMIT, "%s: more than %u vertices", c->name, MAX_COUNT);
    if (!grow((void **)&m->vertices, &b->vertex_capacity, (uint64_t)m->vertex_count + 1, 3 * sizeof(float)))
        return fc_error_set(err, FC_ERR_NOMEM, "%s: no memory for %u vertices", c->name, (unsigned)m->vertex_count);
    for (int k = 0; k < 3; k++)
        m->vertices[3 * (size_t)m->vertex_count + k] = (float)xyz[k];
    m->vertex_count++;
    return FC_OK;
}

fc_code fc_mesh_builder_polygon(fc_mesh_builder *b, const fc_cursor *c, const uint64_t *indices, uint64_t count,
                                fc_error *err)
{
    fc_mesh_data *m = &b->mesh;
    if (count < 3)
        return fc_cursor_fail(c, err, "a face of %llu corners (at least 3 are needed)", (unsigned long long)count);
    for (uint64_t i = 0; i < count; i++)
        if (indices[i] >= m->vertex_count)
            return fc_cursor_fail(c, err, "a face refers to vertex %llu, but there are %u vertices",
                                  (unsigned long long)indices[i], (unsigned)m->vertex_count);
    uint64_t total = (uint64_t)m->triangle_count + (count - 2);
    if (total > MAX_COUNT)
        return fc_error_set(err, FC_ERR_LIMIT, "%s: more than %u triangles", c->name, MAX_COUNT);
    if (!grow((void **)&m->indices, &b->triangle_capacity, total, 3 * sizeof(uint32_t)))
        return fc_error_set(err, FC_ERR_NOMEM, "%s: no memory for %llu triangles", c->name, (unsigned long long)total);
    for (uint64_t i = 1; i + 1 < count; i++) {
        uint32_t *t = m->indices + 3 * (size_t)m->triangle_count++;
        t[0] = (uint32_t)indices[0];
        t[1] = (uint32_t)indices[i];
        t[2] = (uint32_t)indices[i + 1];
    }
    return FC_OK;
}

fc_code fc_mesh_builder_finish(fc_mesh_builder *b, const fc_cursor *c, fc_mesh_data *out, fc_error *err)
{
    if (b->mesh.triangle_count == 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: no triangles (a mesh needs faces)", c->name);
    *out = b->mesh;
    *b = (fc_mesh_builder){0};
    return FC_OK;
}

void fc_mesh_data_free(fc_mesh_data *m)
{
    free(m->vertices);
    free(m->indices);
    *m = (fc_mesh_data){0};
}

void fc_mesh_builder_free(fc_mesh_builder *b)
{
    fc_mesh_data_free(&b->mesh);
    *b = (fc_mesh_builder){0};
}
