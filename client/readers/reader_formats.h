/* reader_formats.h — internal to the particle readers: one entry point per file
 * format. Each reads the whole of c's data into *frame (zeroed by the caller).
 * On failure the frame may hold partial data: fc_read_particles_mem frees it. */
#ifndef FC_READER_FORMATS_H
#define FC_READER_FORMATS_H

#include "fluidcast_types.h"
#include "reader_cursor.h"

fc_code fc_read_f32(fc_cursor *c, fc_frame *frame, fc_error *err);
fc_code fc_read_ply(fc_cursor *c, fc_frame *frame, fc_error *err);
fc_code fc_read_vtk(fc_cursor *c, fc_frame *frame, fc_error *err);
fc_code fc_read_csv(fc_cursor *c, fc_frame *frame, fc_error *err);
fc_code fc_read_bgeo(fc_cursor *c, fc_frame *frame, fc_error *err);
fc_code fc_read_npy(fc_cursor *c, fc_frame *frame, fc_error *err);
/* HDF5 (libhdf5, from the bytes in memory): reader_hdf5.c. c's data has the HDF5
 * signature (fc_is_hdf5): the caller, fc_read_particles_mem, has checked it. */
fc_code fc_read_hdf5(fc_cursor *c, fc_frame *frame, fc_error *err);
fc_code fc_read_vtkxml(fc_cursor *c, fc_frame *frame, fc_error *err);
/* A .pvd collection's first DataSet file attribute, copied into file (NUL-terminated). */
fc_code fc_pvd_first_dataset(fc_cursor *c, char *file, size_t file_size, fc_error *err);

#endif
