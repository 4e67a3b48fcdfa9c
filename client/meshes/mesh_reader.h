/* mesh_reader.h — triangle meshes from the files solvers export their
 * geometry in (tanks, obstacles, rigid bodies): Wavefront OBJ (v and f lines;
 * polygons fanned into triangles; negative indices counting back from the
 * last vertex), STL (binary and ascii), PLY with a face element (ascii,
 * binary little- and big-endian) and legacy VTK POLYDATA (POLYGONS and
 * TRIANGLE_STRIPS, ascii and binary, the 4.x and the 5.1 OFFSETS/CONNECTIVITY
 * layouts) and VTK XML PolyData .vtp (one Piece's Polys; ascii, base64 or
 * appended raw data, zlib-compressed or not). A bad file gets FC_ERR_PARSE naming the file and the place (line
 * or byte offset) and what is wrong, never a crash; a file beyond the protocol's
 * limits (2^24 vertices or triangles) FC_ERR_LIMIT. */
#ifndef FC_MESH_READER_H
#define FC_MESH_READER_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef enum fc_mesh_format {
    FC_MESH_FILE_UNKNOWN = 0,
    FC_MESH_FILE_OBJ,
    FC_MESH_FILE_STL,
    FC_MESH_FILE_PLY,
    FC_MESH_FILE_VTK,
    FC_MESH_FILE_VTP
} fc_mesh_format;

/* The arrays of a mesh read from a file (malloc'd; fc_mesh_data_free). */
typedef struct fc_mesh_data {
    float *vertices;            /* 3 V */
    uint32_t *indices;          /* 3 T, each < V */
    uint32_t vertex_count;
    uint32_t triangle_count;    /* >= 1 for a mesh read successfully */
} fc_mesh_data;

/* Frees the arrays (defined beside the code that grows them, mesh_builder.c). */
void fc_mesh_data_free(fc_mesh_data *m);

/* From the extension, case-insensitive: .obj .stl .ply .vtk .vtp. */
fc_mesh_format fc_mesh_format_from_path(const char *path);

/* Reads a mesh file of the format its name says. FC_ERR_IO when it cannot be
 * read, FC_ERR_USAGE for an unknown extension. */
fc_code fc_read_mesh(const char *path, fc_mesh_data *out, fc_error *err);

/* The same from memory; `name` (with its extension) picks the format and
 * names the file in messages. */
fc_code fc_read_mesh_mem(const char *name, const uint8_t *data, size_t size, fc_mesh_data *out, fc_error *err);

#endif
