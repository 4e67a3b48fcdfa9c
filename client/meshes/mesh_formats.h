/* mesh_formats.h — internal to the mesh readers: one entry point per file
 * format (mesh_*.c), called by the dispatcher (mesh_reader.c). Each reads the
 * whole of c's data into the builder, which the caller finishes or frees. */
#ifndef FC_MESH_FORMATS_H
#define FC_MESH_FORMATS_H

#include "fluidcast_types.h"
#include "mesh_builder.h"
#include "reader_cursor.h"

fc_code fc_read_mesh_obj(fc_cursor *c, fc_mesh_builder *b, fc_error *err);
fc_code fc_read_mesh_stl(fc_cursor *c, fc_mesh_builder *b, fc_error *err);
fc_code fc_read_mesh_ply(fc_cursor *c, fc_mesh_builder *b, fc_error *err);
fc_code fc_read_mesh_vtk(fc_cursor *c, fc_mesh_builder *b, fc_error *err);
fc_code fc_read_mesh_vtp(fc_cursor *c, fc_mesh_builder *b, fc_error *err);

#endif
