/* mesh_check.h — what the surface tests measure on an extracted mesh:
 * topology (every edge in exactly two triangles, once each way: a closed,
 * consistently oriented 2-manifold; Euler characteristic; connected parts)
 * and geometry (enclosed volume, mean distance from a point, outward faces). */
#ifndef FC_MESH_CHECK_H
#define FC_MESH_CHECK_H

#include <stdbool.h>
#include <stdint.h>

#include "fc_surface_mesh.h"

typedef struct mesh_topology {
    bool closed_manifold;     /* each directed edge once, its reverse once: no border, no crack, no fold */
    uint64_t edges;           /* undirected */
    int64_t euler;            /* V - E + F */
    uint32_t components;      /* connected parts (by shared vertices) */
    uint32_t unused_vertices; /* in no triangle */
} mesh_topology;

mesh_topology mesh_check_topology(const fc_surface_mesh *m);

/* The enclosed volume (divergence theorem: positive when the faces point out). */
double mesh_volume(const fc_surface_mesh *m);

/* The mean distance of the vertices from c. */
double mesh_mean_distance(const fc_surface_mesh *m, const double c[3]);

/* The fraction of triangles whose normal (counter-clockwise) points away from c. */
double mesh_outward_faces(const fc_surface_mesh *m, const double c[3]);

/* The fraction of vertex normals on the same side as the area-weighted
 * normal of the triangles around the vertex. */
double mesh_normals_agree(const fc_surface_mesh *m);

#endif
