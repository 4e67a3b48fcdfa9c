/* mesh_buffer_cache.c — see mesh_buffer_cache.h. */
#include "gpu/mesh_buffer_cache.h"

#include <stdbool.h>
#include <string.h>

#include "fc_error.h"

static void clear_entry(fc_mesh_buffer_entry *e)
{
    fc_mesh_buffers_destroy(e->buffers);
    fc_mesh_geometry_unref(e->geometry);
    *e = (fc_mesh_buffer_entry){0};
}

/* Only the cache holds it: no connection, session or queued job can name it again. */
static void drop_orphans(fc_mesh_buffer_cache *c)
{
    for (int i = 0; i < FC_MESH_BUFFER_CACHE_SIZE; i++)
        if (c->entries[i].geometry && atomic_load(&c->entries[i].geometry->refs) == 1)
            clear_entry(&c->entries[i]);
}

static fc_mesh_buffer_entry *find(fc_mesh_buffer_cache *c, const fc_mesh_geometry *g)
{
    for (int i = 0; i < FC_MESH_BUFFER_CACHE_SIZE; i++)
        if (c->entries[i].geometry == g)
            return &c->entries[i];
    return NULL;
}

/* A free entry, else the least recently used one not stamped `now` (the
 * render being prepared needs those), emptied. */
static fc_mesh_buffer_entry *make_room(fc_mesh_buffer_cache *c, uint64_t now)
{
    fc_mesh_buffer_entry *oldest = NULL;
    for (int i = 0; i < FC_MESH_BUFFER_CACHE_SIZE; i++) {
        fc_mesh_buffer_entry *e = &c->entries[i];
        if (!e->geometry)
            return e;
        if (e->last_used != now && (!oldest || e->last_used < oldest->last_used))
            oldest = e;
    }
    if (oldest)
        clear_entry(oldest);
    return oldest;
}

static fc_code buffers_of(fc_mesh_buffer_cache *c, fc_pipeline *pipeline, fc_mesh_geometry *g, uint64_t now,
                          const fc_mesh_buffers **out, fc_error *err)
{
    fc_mesh_buffer_entry *e = find(c, g);
    if (!e) {
        fc_mesh_buffers *buffers;
        fc_code code = fc_mesh_buffers_create(pipeline, &g->mesh, &buffers, err);
        if (code != FC_OK)
            return code;
        e = make_room(c, now);
        if (!e) {
            fc_mesh_buffers_destroy(buffers);
            return fc_error_set(err, FC_ERR_INTERNAL, "more than %d meshes in one render",
                                FC_MESH_BUFFER_CACHE_SIZE);
        }
        e->geometry = fc_mesh_geometry_ref(g);
        e->buffers = buffers;
    }
    e->last_used = now;
    *out = e->buffers;
    return FC_OK;
}

fc_code fc_mesh_buffer_cache_scene(fc_mesh_buffer_cache *c, fc_pipeline *pipeline, const fc_mesh_set *set,
                                   fc_scene_mesh *out, fc_error *err)
{
    drop_orphans(c);
    uint64_t now = ++c->clock;
    for (uint32_t i = 0; i < set->count; i++) {
        const fc_mesh_entry *e = &set->entries[i];
        const fc_mesh *mesh = &e->geometry->mesh;
        fc_scene_mesh *m = &out[i];
        fc_code code = buffers_of(c, pipeline, e->geometry, now, &m->buffers, err);
        if (code != FC_OK)
            return code;
        memcpy(m->transform, e->transform, sizeof m->transform);
        memcpy(m->color, mesh->color, sizeof m->color);
        m->opacity = mesh->opacity;
        m->hide_near = (mesh->flags & FC_MESH_HIDE_NEAR) != 0;
    }
    return FC_OK;
}

void fc_mesh_buffer_cache_free(fc_mesh_buffer_cache *c)
{
    for (int i = 0; i < FC_MESH_BUFFER_CACHE_SIZE; i++)
        if (c->entries[i].geometry)
            clear_entry(&c->entries[i]);
    c->clock = 0;
}
