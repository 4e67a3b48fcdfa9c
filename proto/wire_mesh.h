/* wire_mesh.h — the mesh messages: a triangle mesh drawn with the fluid
 * (MESH, type 12) and new placements of meshes already sent (MESH_TRANSFORM,
 * type 13). Normative description: proto/PROTOCOL.md, section 12. Same
 * conventions as wire.h. */
#ifndef FC_WIRE_MESH_H
#define FC_WIRE_MESH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "wire.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FC_MESH_FIXED_SIZE 80u              /* MESH bytes before the vertices */
#define FC_MESH_WIRE_NORMALS 1u             /* MESH flags bit 0: per-vertex normals follow the indices */
#define FC_MESH_WIRE_FLAGS (FC_MESH_WIRE_NORMALS | FC_MESH_HIDE_NEAR)
#define FC_MESH_MAX_VERTICES (1u << 24)     /* V per MESH */
#define FC_MESH_MAX_TRIANGLES (1u << 24)    /* T per MESH */
#define FC_MESH_MAX_COUNT 64u               /* meshes one connection (or one session) holds; entries per
                                               MESH_TRANSFORM */
#define FC_MESH_TRANSFORM_ENTRY_SIZE 52u    /* id + 12 floats */

/* The identity placement, for fc_mesh.transform. */
void fc_mesh_identity(float transform[12]);

/* Checks a mesh as a receiver does (PROTOCOL.md 12.1, steps 4-6): counts
 * within FC_MESH_MAX_*, T = 0 only with V = 0, colour and opacity in [0, 1],
 * a finite transform, finite vertices and normals, every index < V.
 * FC_ERR_LIMIT or FC_ERR_INVALID_VALUE naming the vertex or triangle. */
fc_code fc_mesh_validate(const fc_mesh *mesh, fc_error *err);

/* MESH: the mesh's fields and arrays (normals only when mesh->normals is set).
 * The mesh is validated first (fc_mesh_validate's codes); FC_ERR_TOO_LARGE
 * beyond the u32 length field. */
fc_code fc_wire_write_mesh(fc_buf *out, uint32_t request_id, const fc_mesh *mesh, fc_error *err);

/* MESH removing mesh `id`: V = T = 0, no arrays. */
fc_code fc_wire_write_mesh_removal(fc_buf *out, uint32_t request_id, uint32_t id, fc_error *err);

/* Decodes and checks a MESH. The arrays are copied into one allocation,
 * *storage, which out's pointers point into (NULL for a removal, T = 0); the
 * caller frees it with free(). Errors in the order of PROTOCOL.md 12.1. */
fc_code fc_wire_read_mesh(const uint8_t *p, size_t n, fc_mesh *out, void **storage, fc_error *err);

/* MESH_TRANSFORM: `count` entries (at most FC_MESH_MAX_COUNT, ids distinct,
 * transforms finite). */
fc_code fc_wire_write_mesh_transforms(fc_buf *out, uint32_t request_id, const fc_mesh_transform *entries,
                                      uint32_t count, fc_error *err);

/* Decodes a MESH_TRANSFORM into entries[FC_MESH_MAX_COUNT]. Errors in the
 * order of PROTOCOL.md 12.2. */
fc_code fc_wire_read_mesh_transforms(const uint8_t *p, size_t n, fc_mesh_transform entries[FC_MESH_MAX_COUNT],
                                     uint32_t *count, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
