/* reader_hdf5_loader.c — the fluidcast command's fc_read_hdf5 (reader_formats.h):
 * the HDF5 reader from fluidcast-hdf5.so (hdf5_module.h), opened when a file is
 * HDF5. Compiled into the executable itself, not into a library: defined before
 * any archive is searched, it keeps fc_readers' own reader_hdf5.o (and with
 * --as-needed, libhdf5) out of the executable; a second definition would be a
 * link error, not a silent choice. The view module links fc_readers whole. */
#include "cli_module.h"
#include "hdf5_module.h"

fc_code fc_read_hdf5(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    fc_cli_module module;
    fc_code code = fc_cli_module_open(FC_HDF5_MODULE_FILE, FC_HDF5_MODULE_SYMBOL, FC_HDF5_MODULE_ABI,
                                      "reading HDF5", &module, err);
    if (code != FC_OK)
        return code;
    const fc_hdf5_module *hdf5 = module.api;
    code = hdf5->read(c, frame, err);
    fc_cli_module_close(&module);
    return code;
}
