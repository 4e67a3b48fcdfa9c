/* surface_tets.h — the tables of marching tetrahedra on the Kuhn
 * (Freudenthal) triangulation of the cube: each cell split into the six
 * tetrahedra 0 -> e_a -> e_a + e_b -> (1,1,1) along its main diagonal, one per
 * order (a, b, c) of the axes. Every cell splits its faces along the same
 * diagonals as its neighbours, so the tetrahedra of the whole grid meet face
 * to face, and each tetrahedron cuts the isosurface into zero, one or two
 * triangles with no ambiguity: the surface is closed and 2-manifold by
 * construction, unlike marching cubes' ambiguous faces.
 *
 * A corner of a cell is a 3-bit code x | y << 1 | z << 2. The lattice edges
 * a vertex can lie on go from a point to the point plus one of seven
 * directions (surface_common.glsl: x, y, z, xy, xz, yz, xyz). */
#ifndef FC_SURFACE_TETS_H
#define FC_SURFACE_TETS_H

#include <stdint.h>

#define FC_SURFACE_TETS 6u
#define FC_SURFACE_TET_CASES 16u

/* corners[t]: tetrahedron t's four corner codes, 3 bits each (vertex v at
 * bits 3v). cases[16 t + m], m the mask of its vertices inside (field >= iso):
 * bits 0-1 the triangle count (0-2), then per triangle three tetrahedron edges
 * (3 bits each; edge k joins the vertex pair FC_SURFACE_TET_EDGES[k]), counter-
 * clockwise seen from outside. */
void fc_surface_tet_tables(uint32_t corners[FC_SURFACE_TETS], uint32_t cases[FC_SURFACE_TETS * FC_SURFACE_TET_CASES]);

/* The vertex pairs of a tetrahedron's six edges, lower vertex first. */
extern const uint8_t FC_SURFACE_TET_EDGES[6][2];

#endif
