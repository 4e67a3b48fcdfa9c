/* cli_module.h — the fluidcast command's heavy parts as shared modules,
 * opened with dlopen() when a command first needs one:
 *   fluidcast-image.so  OpenImageIO (--legend: the server's image decoded and encoded again)
 *   fluidcast-video.so  libavcodec/libavformat/libswscale (render to .mp4/.webm)
 *   fluidcast-view.so   the whole of `fluidcast view`: SDL2, libavcodec's decoders, the SpaceMouse
 *   fluidcast-hdf5.so   the HDF5 particle reader (libhdf5), for HDF5 input files
 * Linked into the executable, their libraries (OpenImageIO alone pulls in 261)
 * cost every run about 0.2 s of CPU to load, a command that never touches them
 * included (bench/RESULTS.md, "The CLI's start-up"). A missing or broken module
 * fails only the command that needs it.
 *
 * Where: the directory $FLUIDCAST_MODULE_DIR when set (tests, relocated
 * installs), else FC_MODULE_RELDIR relative to the executable's own directory
 * (/proc/self/exe): ../lib/<multiarch>/fluidcast from bin/ when installed, and
 * the same layout in the build tree.
 *
 * A module exports one const object, its interface: a struct of function
 * pointers declared by the CLI (image_module.h, video_module.h, view_module.h, hdf5_module.h) whose first
 * member is the interface's ABI version, checked here. */
#ifndef FC_CLI_MODULE_H
#define FC_CLI_MODULE_H

#include <stdint.h>

#include "fluidcast_types.h"

#define FC_MODULE_DIR_ENV "FLUIDCAST_MODULE_DIR"
#define FC_MODULE_PATH_MAX 4096

/* One opened module. The caller owns it and closes it when done. */
typedef struct fc_cli_module {
    void *handle;                     /* dlopen()'s */
    const void *api;                  /* the exported interface; starts with its uint32_t ABI version */
    char path[FC_MODULE_PATH_MAX];    /* the file opened, for messages */
} fc_cli_module;

/* The module file `file` (e.g. "fluidcast-image.so"): its directory ($FLUIDCAST_MODULE_DIR
 * or next to the executable, see above) and name, into path. FC_ERR_IO when the
 * executable's path cannot be read, FC_ERR_USAGE when the result does not fit. */
fc_code fc_cli_module_path(const char *file, char path[FC_MODULE_PATH_MAX], fc_error *err);

/* Opens `file` and looks up its interface `symbol`, which must start with
 * `abi`. FC_ERR_IO naming the file and what failed (dlopen()'s or dlsym()'s
 * message, or the two ABI versions); *m is then empty. `purpose` says which
 * option needs it, for the message ("--legend", "video output"). */
fc_code fc_cli_module_open(const char *file, const char *symbol, uint32_t abi, const char *purpose,
                           fc_cli_module *m, fc_error *err);

/* Releases *m (the code stays mapped: the libraries it loaded may have started
 * threads, so nothing is unloaded); an empty or closed module is ignored. */
void fc_cli_module_close(fc_cli_module *m);

#endif
