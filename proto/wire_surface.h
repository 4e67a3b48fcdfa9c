/* wire_surface.h — the surface messages (issue 27): SURFACE (25) asks for the
 * extracted surface mesh of the frame a RENDER would render, SURFACE_PART (26)
 * carries the answer in parts. Normative description: proto/PROTOCOL.md,
 * section 13. Same conventions as wire.h.
 *
 * The mesh travels as one body (positions, normals, indices, then the
 * attribute arrays the reply has, in FC_SURFACE_* bit order, all little-endian
 * 32-bit words) cut into parts of FC_SURFACE_PART_DATA_MAX bytes, so no message
 * grows with the mesh and a receiver holds only the bytes that have arrived. */
#ifndef FC_WIRE_SURFACE_H
#define FC_WIRE_SURFACE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fc_surface_mesh.h"
#include "fluidcast_types.h"
#include "wire.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FC_SURFACE_ATTRIBUTES_ALL 15u           /* every FC_SURFACE_* bit */
#define FC_SURFACE_REQUEST_SIZE 4u              /* SURFACE: `attributes` */
#define FC_SURFACE_PART_FIXED_SIZE 36u          /* SURFACE_PART bytes before its data */
#define FC_SURFACE_PART_DATA_MAX (16u << 20)    /* body bytes per part (the last may hold fewer) */
#define FC_SURFACE_MAX_VERTICES (1u << 25)      /* V of one reply */
#define FC_SURFACE_MAX_TRIANGLES (1u << 26)     /* T of one reply */

/* Bytes of the body of a mesh of V vertices, T triangles and attribute bits A. */
uint64_t fc_surface_body_size(uint32_t vertex_count, uint32_t triangle_count, uint32_t attributes);
/* Parts K a body of that many bytes travels in: at least 1. */
uint32_t fc_surface_part_count(uint64_t body_size);

/* Checks a mesh as a receiver does once it is whole (PROTOCOL.md 13.3): counts
 * within FC_SURFACE_MAX_*, T = 0 exactly when V = 0, attribute bits known and
 * their arrays present, positions, normals, speeds, densities and velocities
 * finite, every index < V. FC_ERR_LIMIT or FC_ERR_INVALID_VALUE naming the
 * vertex or triangle. */
fc_code fc_surface_mesh_validate(const fc_surface_mesh *mesh, fc_error *err);

/* SURFACE: which attribute arrays the client wants (FC_SURFACE_* bits). */
fc_code fc_wire_write_surface_request(fc_buf *out, uint32_t request_id, uint32_t attributes, fc_error *err);
/* MALFORMED unless exactly FC_SURFACE_REQUEST_SIZE bytes; INVALID_VALUE for unknown bits. */
fc_code fc_wire_read_surface_request(const uint8_t *p, size_t n, uint32_t *attributes, fc_error *err);

/* SURFACE_PART `index` (0-based, below fc_surface_part_count) of the reply
 * carrying `mesh`, which must pass fc_surface_mesh_validate; extract_ms is the
 * server's extraction time (negative: not measured). */
fc_code fc_wire_write_surface_part(fc_buf *out, uint32_t request_id, const fc_surface_mesh *mesh, float extract_ms,
                                   uint32_t index, fc_error *err);

/* A reply being received: feed it each SURFACE_PART payload in arrival order.
 * It checks every part against the first (PROTOCOL.md 13.3) before taking its
 * bytes, and grows only by the bytes that arrived, never by what a count
 * announces, so a hostile count costs nothing before its bytes come. */
typedef struct fc_surface_assembly {
    uint64_t max_body;          /* the receiver's own bound on the body's bytes */
    uint32_t next_index;        /* parts taken so far */
    uint32_t part_count;        /* K, V, T, A of the first part */
    uint32_t vertex_count;
    uint32_t triangle_count;
    uint32_t attributes;
    float extract_ms;
    uint64_t body_size;
    uint8_t *body;              /* the bytes received, in body order */
    size_t received;
} fc_surface_assembly;

/* max_body 0 means the largest body the FC_SURFACE_MAX_* counts allow. */
void fc_surface_assembly_init(fc_surface_assembly *a, uint64_t max_body);
void fc_surface_assembly_free(fc_surface_assembly *a);
/* Takes one part; *complete becomes true with the last. A refused part
 * (MALFORMED, INCONSISTENT, LIMIT, NOMEM) leaves the assembly failed: free it. */
fc_code fc_surface_assembly_add(fc_surface_assembly *a, const uint8_t *p, size_t n, bool *complete, fc_error *err);
/* Moves a complete reply's mesh into *out (arrays of its own, host order,
 * fc_surface_mesh_free releases them) after fc_surface_mesh_validate;
 * *extract_ms may be NULL. */
fc_code fc_surface_assembly_finish(fc_surface_assembly *a, fc_surface_mesh *out, float *extract_ms, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
