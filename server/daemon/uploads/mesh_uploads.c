/* mesh_uploads.c — see mesh_uploads.h. */
#include "uploads/mesh_uploads.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

fc_mesh_geometry *fc_mesh_geometry_ref(fc_mesh_geometry *g)
{
    atomic_fetch_add(&g->refs, 1);
    return g;
}

void fc_mesh_geometry_unref(fc_mesh_geometry *g)
{
    if (!g || atomic_fetch_sub(&g->refs, 1) != 1)
        return;
    free(g->storage);
    free(g);
}

uint64_t fc_mesh_geometry_bytes(const fc_mesh_geometry *g)
{
    if (!g)
        return 0;
    uint64_t per_vertex = g->mesh.normals ? 24u : 12u;
    return FC_MESH_OVERHEAD_BYTES + per_vertex * g->mesh.vertex_count + 12u * (uint64_t)g->mesh.triangle_count;
}

fc_code fc_mesh_geometry_decode(const uint8_t *payload, size_t n, fc_mesh_geometry **out, uint32_t *id,
                                fc_error *err)
{
    *out = NULL;
    fc_mesh mesh;
    void *storage;
    fc_code code = fc_wire_read_mesh(payload, n, &mesh, &storage, err);
    if (code != FC_OK)
        return code;
    *id = mesh.id;
    if (mesh.triangle_count == 0)
        return FC_OK;
    fc_mesh_geometry *g = calloc(1, sizeof *g);
    if (!g) {
        free(storage);
        return fc_error_set(err, FC_ERR_NOMEM, "MESH %u: out of memory", (unsigned)mesh.id);
    }
    atomic_init(&g->refs, 1);
    g->mesh = mesh;
    g->storage = storage;
    *out = g;
    return FC_OK;
}

int fc_mesh_set_find(const fc_mesh_set *s, uint32_t id)
{
    for (uint32_t i = 0; i < s->count; i++)
        if (s->entries[i].geometry->mesh.id == id)
            return (int)i;
    return -1;
}

uint64_t fc_mesh_set_bytes(const fc_mesh_set *s)
{
    uint64_t bytes = 0;
    for (uint32_t i = 0; i < s->count; i++)
        bytes += fc_mesh_geometry_bytes(s->entries[i].geometry);
    return bytes;
}

fc_code fc_mesh_set_check_room(const fc_mesh_set *s, uint32_t id, fc_error *err)
{
    if (fc_mesh_set_find(s, id) >= 0 || s->count < FC_MESH_MAX_COUNT)
        return FC_OK;
    return fc_error_set(err, FC_ERR_LIMIT, "MESH %u: this connection holds %u meshes already, the limit",
                        (unsigned)id, FC_MESH_MAX_COUNT);
}

void fc_mesh_set_put(fc_mesh_set *s, fc_mesh_geometry *g)
{
    int at = fc_mesh_set_find(s, g->mesh.id);
    fc_mesh_entry *e;
    if (at >= 0) {
        e = &s->entries[at];
        fc_mesh_geometry_unref(e->geometry);
    } else {
        e = &s->entries[s->count++];
    }
    e->geometry = g;
    memcpy(e->transform, g->mesh.transform, sizeof e->transform);
}

void fc_mesh_set_remove(fc_mesh_set *s, uint32_t id)
{
    int at = fc_mesh_set_find(s, id);
    if (at < 0)
        return;
    fc_mesh_geometry_unref(s->entries[at].geometry);
    /* Keep the others in the order they were sent: that is the draw order. */
    memmove(&s->entries[at], &s->entries[at + 1], (s->count - (uint32_t)at - 1) * sizeof s->entries[0]);
    s->count--;
}

fc_code fc_mesh_set_move(fc_mesh_set *s, const fc_mesh_transform *entries, uint32_t count, fc_error *err)
{
    for (uint32_t i = 0; i < count; i++)
        if (fc_mesh_set_find(s, entries[i].id) < 0)
            return fc_error_set(err, FC_ERR_BAD_STATE, "MESH_TRANSFORM: no mesh %u was sent (entry %u)",
                                (unsigned)entries[i].id, (unsigned)i);
    for (uint32_t i = 0; i < count; i++)
        memcpy(s->entries[fc_mesh_set_find(s, entries[i].id)].transform, entries[i].transform,
               sizeof entries[i].transform);
    return FC_OK;
}

void fc_mesh_set_append(fc_mesh_set *dst, const fc_mesh_set *src)
{
    for (uint32_t i = 0; i < src->count && dst->count < FC_MESH_SET_CAPACITY; i++) {
        fc_mesh_entry *e = &dst->entries[dst->count++];
        *e = src->entries[i];
        fc_mesh_geometry_ref(e->geometry);
    }
}

void fc_mesh_set_free(fc_mesh_set *s)
{
    for (uint32_t i = 0; i < s->count; i++)
        fc_mesh_geometry_unref(s->entries[i].geometry);
    s->count = 0;
}
