/* hdf5_module.h — the interface of fluidcast-hdf5.so (modules/hdf5_module.c):
 * the particle readers' HDF5 format (client/readers/reader_hdf5.c, libhdf5).
 * The command's own fc_read_hdf5 (reader_hdf5_loader.c) opens it with
 * fc_cli_module_open (cli_module.h) when a file is HDF5, so libhdf5 and its
 * 37 libraries (~4 ms of every start) are loaded by nothing else. */
#ifndef FC_HDF5_MODULE_H
#define FC_HDF5_MODULE_H

#include <stdint.h>

#include "reader_formats.h"

#define FC_HDF5_MODULE_FILE "fluidcast-hdf5.so"
#define FC_HDF5_MODULE_SYMBOL "fc_hdf5_module_v1"
/* Raised whenever the struct below, or fc_cursor and what it points to
 * (reader_cursor.h), change: the module is built from the same sources. */
#define FC_HDF5_MODULE_ABI 1u

typedef struct fc_hdf5_module {
    uint32_t abi;   /* FC_HDF5_MODULE_ABI: first, checked when the module is opened */
    /* fc_read_hdf5 (reader_formats.h): the whole of c's data into *frame. */
    fc_code (*read)(fc_cursor *c, fc_frame *frame, fc_error *err);
} fc_hdf5_module;

#endif
