/* surface_cubes.h — the tables of marching cubes, made with one rule for the
 * ambiguous faces so that the surface stays closed, 2-manifold and free of
 * cracks: on each face of a cell the isosurface's trace is a set of segments
 * between the face's crossed edges, chosen from the face's four corners alone
 * (one inside corner, or three, or two across a diagonal: each corner alone on
 * its side is cut off; two side by side: the segment between the two crossed
 * edges), so the two cells sharing a face cut it the same way. Each crossed
 * edge ends one segment and starts the next (segments are directed with the
 * inside on their right, seen from outside the cell), so the segments chain
 * into loops; each loop is fanned into triangles from a vertex none of whose
 * diagonals lies in an ambiguous face (the cell across it could fan the same
 * diagonal, which would then have four triangles). A vertex on a lattice edge
 * then has one segment in each of the edge's four faces: its triangles form
 * one ring, and every mesh edge lies on two triangles.
 *
 * A corner of a cell is a 3-bit code x | y << 1 | z << 2. Cell edge 4 a + j
 * (a the axis, 0..2) goes from the j-th corner (in code order) whose bit a is
 * 0 along axis a: the lattice edge of that corner in direction a. */
#ifndef FC_SURFACE_CUBES_H
#define FC_SURFACE_CUBES_H

#include <stdint.h>

#define FC_SURFACE_CUBE_CASES 256u
/* Room for every case's triangles (at most 12 crossed edges a case, so at
 * most 10 triangles: 256 x 12 is ample). */
#define FC_SURFACE_CUBE_TRIANGLES_MAX 3072u

/* cases[m], m the mask of the cell's corners inside (field >= iso): the index
 * of its first triangle in triangles (bits 0-15) and its triangle count (bits
 * 16-23). triangles[i]: three cell edges, 4 bits each, counter-clockwise seen
 * from outside. Returns the number of triangles written. */
uint32_t fc_surface_cube_tables(uint32_t cases[FC_SURFACE_CUBE_CASES],
                                uint32_t triangles[FC_SURFACE_CUBE_TRIANGLES_MAX]);

/* The corner code where cell edge k starts and its axis. */
uint32_t fc_surface_cube_edge_corner(uint32_t k);

#endif
