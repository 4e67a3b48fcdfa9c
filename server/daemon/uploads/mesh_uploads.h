/* mesh_uploads.h — the meshes a client sent (MESH, MESH_TRANSFORM): decoded
 * and checked on the event loop when they arrive, their arrays shared by
 * reference with the render jobs that draw them, like frames and scene images.
 * A set holds a connection's (or a session's) meshes by id; a render job
 * takes a copy of it, so a later MESH_TRANSFORM never moves a mesh in an
 * image already requested. */
#ifndef FC_DAEMON_MESH_UPLOADS_H
#define FC_DAEMON_MESH_UPLOADS_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>

#include "wire_mesh.h"

/* One uploaded mesh: its arrays, colour, opacity and flags as received.
 * Immutable once created; freed with its last reference, from any thread. */
typedef struct fc_mesh_geometry {
    atomic_uint refs;
    fc_mesh mesh;      /* arrays point into storage; mesh.transform is the one it arrived with */
    void *storage;
} fc_mesh_geometry;

fc_mesh_geometry *fc_mesh_geometry_ref(fc_mesh_geometry *g);
/* NULL is ignored. */
void fc_mesh_geometry_unref(fc_mesh_geometry *g);
/* What a mesh counts beyond its arrays (PROTOCOL.md 6.4): its record here and in the GL thread's cache. */
#define FC_MESH_OVERHEAD_BYTES 256u

/* Bytes it holds as counted against max_session_memory (PROTOCOL.md 6.4):
 * 12 V (24 V with normals) + 12 T + FC_MESH_OVERHEAD_BYTES; 0 for NULL. */
uint64_t fc_mesh_geometry_bytes(const fc_mesh_geometry *g);

/* Decodes a MESH payload (wire_mesh.h's checks and codes): *out a geometry
 * with one reference, or NULL for a removal (T = 0); *id the mesh's id. */
fc_code fc_mesh_geometry_decode(const uint8_t *payload, size_t n, fc_mesh_geometry **out, uint32_t *id,
                                fc_error *err);

/* A placed mesh: a reference to its geometry and where it stands now. */
typedef struct fc_mesh_entry {
    fc_mesh_geometry *geometry;
    float transform[12];
} fc_mesh_entry;

/* Room for a session's meshes and a viewer's own in one render job. */
#define FC_MESH_SET_CAPACITY (2 * FC_MESH_MAX_COUNT)

/* Meshes by id, in the order they were first sent (the draw order). A zeroed
 * set is empty. A connection's or session's set holds at most
 * FC_MESH_MAX_COUNT; a job's copy may hold both. */
typedef struct fc_mesh_set {
    uint32_t count;
    fc_mesh_entry entries[FC_MESH_SET_CAPACITY];
} fc_mesh_set;

/* Index of mesh `id`, or -1. */
int fc_mesh_set_find(const fc_mesh_set *s, uint32_t id);
/* Bytes of the geometry held (each entry's), for the memory limit. */
uint64_t fc_mesh_set_bytes(const fc_mesh_set *s);
/* FC_ERR_LIMIT when adding a new mesh `id` would exceed FC_MESH_MAX_COUNT. */
fc_code fc_mesh_set_check_room(const fc_mesh_set *s, uint32_t id, fc_error *err);
/* Puts `g` (its reference is taken) at its id with its uploaded transform,
 * replacing the mesh of that id; check room first. */
void fc_mesh_set_put(fc_mesh_set *s, fc_mesh_geometry *g);
/* Removes mesh `id`; a mesh never sent is no error (removal is idempotent). */
void fc_mesh_set_remove(fc_mesh_set *s, uint32_t id);
/* Applies a MESH_TRANSFORM atomically: FC_ERR_BAD_STATE naming the first id
 * the set lacks, and then nothing moves. */
fc_code fc_mesh_set_move(fc_mesh_set *s, const fc_mesh_transform *entries, uint32_t count, fc_error *err);
/* Appends src's entries to dst (taking references), as far as dst has room. */
void fc_mesh_set_append(fc_mesh_set *dst, const fc_mesh_set *src);
/* Drops every mesh. */
void fc_mesh_set_free(fc_mesh_set *s);

#endif
