/* output_file.h — the image file the CLI writes: its format from the extension,
 * and writing the received bytes to it. */
#ifndef FC_OUTPUT_FILE_H
#define FC_OUTPUT_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

/* .png, .jpg/.jpeg, .exr (case-insensitive); FC_ERR_USAGE for anything else. */
fc_code fc_output_format_from_path(const char *path, fc_image_format *out, fc_error *err);

/* Upper-case name of a format for messages, e.g. "PNG". */
const char *fc_output_format_name(fc_image_format format);

/* Writes the bytes to path, replacing it. On failure no partial file is left
 * behind: FC_ERR_IO naming the path and the reason. */
fc_code fc_output_write(const char *path, const uint8_t *data, size_t size, fc_error *err);

#endif
