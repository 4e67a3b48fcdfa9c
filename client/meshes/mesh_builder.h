/* mesh_builder.h — internal to the mesh readers: growing vertex and index
 * arrays within the protocol's limits, polygons fanned into triangles, every
 * index and coordinate checked as it comes (cursor-style messages). The
 * bottom of the mesh readers: the format readers (mesh_formats.h) fill a
 * builder, the dispatcher (mesh_reader.c) calls them and finishes it; the
 * builder calls neither. */
#ifndef FC_MESH_BUILDER_H
#define FC_MESH_BUILDER_H

#include <stdbool.h>
#include <stdint.h>

#include "mesh_reader.h"
#include "reader_cursor.h"

typedef struct fc_mesh_builder {
    fc_mesh_data mesh;
    uint32_t vertex_capacity;
    uint32_t triangle_capacity;
} fc_mesh_builder;

/* The next vertex; PARSE for a coordinate that is not finite, LIMIT past 2^24. */
fc_code fc_mesh_builder_vertex(fc_mesh_builder *b, const fc_cursor *c, const double xyz[3], fc_error *err);
/* A polygon of `count` indices (each already made absolute, checked < V here)
 * as count - 2 triangles fanned from its first corner; PARSE below 3 corners
 * or for an index past the vertices, LIMIT past 2^24 triangles. */
fc_code fc_mesh_builder_polygon(fc_mesh_builder *b, const fc_cursor *c, const uint64_t *indices, uint64_t count,
                                fc_error *err);
/* Room for `count` more vertices (a hint from a header; LIMIT when beyond 2^24). */
fc_code fc_mesh_builder_reserve(fc_mesh_builder *b, const fc_cursor *c, uint64_t vertices, uint64_t triangles,
                                fc_error *err);
/* Hands the arrays over (PARSE when the file held no triangle); the builder is emptied. */
fc_code fc_mesh_builder_finish(fc_mesh_builder *b, const fc_cursor *c, fc_mesh_data *out, fc_error *err);
void fc_mesh_builder_free(fc_mesh_builder *b);

#endif
