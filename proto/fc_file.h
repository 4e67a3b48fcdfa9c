/* fc_file.h — reading a whole file into memory, for every reader of the
 * project that needs a file's bytes at once (particle collections, meshes,
 * scene images, camera paths, shaders, tokens). */
#ifndef FC_FILE_H
#define FC_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

/* Reads the file at `path` into a malloc'd buffer (*data, free it), followed
 * by one NUL byte not counted in *size so that text can be read as a string.
 * Regular files, pipes and character devices are read to their end; a file
 * holding more than max_bytes is refused once that many were read (SIZE_MAX:
 * memory is the only limit). Every error names the file:
 *   FC_ERR_IO        "PATH: cannot open: REASON", "PATH: cannot read: REASON",
 *                    "PATH: not a regular file" (a directory, a socket)
 *   FC_ERR_TOO_LARGE "PATH: larger than MAX bytes"
 *   FC_ERR_NOMEM     "PATH: no memory for N bytes"
 * Nothing is left allocated on failure (*data NULL, *size 0). */
fc_code fc_read_file(const char *path, size_t max_bytes, uint8_t **data, size_t *size, fc_error *err);

#endif
