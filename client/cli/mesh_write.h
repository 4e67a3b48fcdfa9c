/* mesh_write.h — surface meshes (fc_surface_mesh) written to files for other
 * programs: binary PLY and VTK XML PolyData (.vtp), which carry the per-vertex
 * normals and attributes, Wavefront OBJ (positions and normals) and binary STL
 * (triangles with their face normals). The format is the path's extension. */
#ifndef FC_MESH_WRITE_H
#define FC_MESH_WRITE_H

#include <stdint.h>
#include <stdio.h>

#include "fluidcast.h"

typedef enum fc_mesh_file_format {
    FC_MESH_FILE_PLY,
    FC_MESH_FILE_OBJ,
    FC_MESH_FILE_VTP,
    FC_MESH_FILE_STL
} fc_mesh_file_format;

/* The format of a path by its extension (case-insensitive): FC_ERR_USAGE
 * naming the extensions known otherwise. */
fc_code fc_mesh_file_format_of(const char *path, fc_mesh_file_format *out, fc_error *err);

/* Writes `mesh` to `path` in the format of its extension: to PATH.part first,
 * renamed at the end, so a file of that name is always whole. FC_ERR_IO
 * naming the file. */
fc_code fc_mesh_write_file(const char *path, const fc_surface_mesh *mesh, fc_error *err);

/* The writers, on an open stream; FC_ERR_IO when a write fails. */
fc_code fc_mesh_write_ply(FILE *to, const fc_surface_mesh *mesh, fc_error *err);
fc_code fc_mesh_write_obj(FILE *to, const fc_surface_mesh *mesh, fc_error *err);
fc_code fc_mesh_write_vtp(FILE *to, const fc_surface_mesh *mesh, fc_error *err);
fc_code fc_mesh_write_stl(FILE *to, const fc_surface_mesh *mesh, fc_error *err);

#endif
