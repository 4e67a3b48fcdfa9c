/* mesh_buffer_cache.h — the GL thread's buffers of client meshes.
 *
 * A mesh is uploaded to the GPU once and drawn by every render that names it
 * until nobody holds it any more: the cache keeps a reference to each
 * geometry it has buffers for (so a cached pointer is always the live
 * geometry, never a new one at a reused address), drops entries whose
 * geometry only it still holds at the next lookup, and evicts the least
 * recently used entry when full. GL thread only. */
#ifndef FC_DAEMON_MESH_BUFFER_CACHE_H
#define FC_DAEMON_MESH_BUFFER_CACHE_H

#include <stdint.h>

#include "render/pipeline.h"
#include "uploads/mesh_uploads.h"

/* Room for two full sets (a session's and a viewer's) and some others'. */
#define FC_MESH_BUFFER_CACHE_SIZE 256

typedef struct fc_mesh_buffer_entry {
    fc_mesh_geometry *geometry;   /* a reference; NULL: the entry is free */
    fc_mesh_buffers *buffers;
    uint64_t last_used;
} fc_mesh_buffer_entry;

/* A zeroed struct is an empty cache. */
typedef struct fc_mesh_buffer_cache {
    fc_mesh_buffer_entry entries[FC_MESH_BUFFER_CACHE_SIZE];
    uint64_t clock;
} fc_mesh_buffer_cache;

/* The meshes of `set` as the pipeline draws them (out[set->count]), their
 * buffers made through `pipeline` where not cached. Errors of
 * fc_mesh_buffers_create (FC_ERR_RENDER when the GPU's memory runs out). */
fc_code fc_mesh_buffer_cache_scene(fc_mesh_buffer_cache *c, fc_pipeline *pipeline, const fc_mesh_set *set,
                                   fc_scene_mesh *out, fc_error *err);

/* Deletes every buffer (before the pipeline's context goes) and drops the references. */
void fc_mesh_buffer_cache_free(fc_mesh_buffer_cache *c);

#endif
