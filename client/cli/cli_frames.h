/* cli_frames.h — the images of a sequence on disk: choosing their format from
 * an option, naming them DIR/PREFIX_NNNNNN.EXT, creating the directory. */
#ifndef FC_CLI_FRAMES_H
#define FC_CLI_FRAMES_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

/* "png", "jpg"/"jpeg", "exr", "raw" or "h264" (a viewer's video stream: `watch` only). */
fc_code fc_cli_parse_format(const char *option, const char *text, fc_image_format *out, fc_error *err);

/* The file extension of a format, without the dot: "png", "jpg", "exr", "raw", "h264". */
const char *fc_cli_format_extension(fc_image_format format);

/* Creates the directory unless it exists. FC_ERR_IO naming it otherwise. */
fc_code fc_cli_ensure_dir(const char *dir, fc_error *err);

/* The directory part of an output path or pattern ("frames/f_%04d.png"),
 * created when missing (one level); nothing for a name without one. */
fc_code fc_cli_ensure_parent_dir(const char *path, fc_error *err);

/* DIR/PREFIX_NNNNNN.EXT (the number zero-padded to 6 digits) into out.
 * FC_ERR_USAGE when it does not fit. */
fc_code fc_cli_frame_path(char *out, size_t size, const char *dir, const char *prefix, uint64_t number,
                          fc_image_format format, fc_error *err);

#endif
