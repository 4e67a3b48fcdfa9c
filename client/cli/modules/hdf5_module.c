/* hdf5_module.c — fluidcast-hdf5.so: the HDF5 particle reader behind
 * hdf5_module.h. The only symbol it exports is the interface; libhdf5 comes
 * with it. */
#include "hdf5_module.h"

__attribute__((visibility("default"))) extern const fc_hdf5_module fc_hdf5_module_v1;

const fc_hdf5_module fc_hdf5_module_v1 = {
    .abi = FC_HDF5_MODULE_ABI,
    .read = fc_read_hdf5,
};
