/* fc_surface_mesh.h — an extracted fluid surface (issue 27): what the daemon's
 * extractor (server/render/surface_extract.h) produces and what a client
 * receives and writes to files. Shared by both sides, so it lives in proto/. */
#ifndef FLUIDCAST_SURFACE_MESH_H
#define FLUIDCAST_SURFACE_MESH_H

#include <stdint.h>

#include "fc_api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An extracted fluid surface: welded, indexed triangles (counter-clockwise seen from outside) with unit
 * outward normals from the field's gradient, and particle attributes interpolated to the vertices. */
enum { FC_SURFACE_SPEED = 1u, FC_SURFACE_DENSITY = 2u, FC_SURFACE_VELOCITY = 4u, FC_SURFACE_ID = 8u };
typedef struct fc_surface_mesh {
    uint32_t vertex_count;
    uint32_t triangle_count;
    float *positions;      /* vertex_count * 3 */
    float *normals;        /* vertex_count * 3 */
    uint32_t *indices;     /* triangle_count * 3 */
    uint32_t attributes;   /* FC_SURFACE_* bits: which arrays below are set */
    float *speed;          /* vertex_count, or NULL */
    float *density;        /* vertex_count, or NULL */
    float *velocity;       /* vertex_count * 3, or NULL */
    uint32_t *id;          /* vertex_count: the nearest particle's id, or NULL */
} fc_surface_mesh;

FC_API void fc_surface_mesh_free(fc_surface_mesh *mesh); /* frees the arrays, zeroes the struct */

#ifdef __cplusplus
}
#endif
#endif
