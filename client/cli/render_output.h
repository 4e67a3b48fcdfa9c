/* render_output.h — where `fluidcast render` puts its images: one video file
 * (video_encoder.h, from RAW RGBA the server sends) or one image file per
 * frame, named by the -o pattern and the frame's number, written as the
 * server encoded them. */
#ifndef FC_RENDER_OUTPUT_H
#define FC_RENDER_OUTPUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast.h"
#include "render_options.h"
#include "video_encoder.h"

typedef struct fc_render_output {
    const fc_render_options *options;
    fc_video_encoder *video;    /* NULL for an image pattern */
} fc_render_output;

/* Opens the video (header written), or creates the pattern's directory when
 * it is missing (one level). FC_ERR_USAGE/FC_ERR_IO as fc_video_open. */
fc_code fc_render_output_open(const fc_render_options *o, fc_render_output *out, fc_error *err);

/* The image file of frame `number` (image patterns only). */
fc_code fc_render_output_path(const fc_render_output *out, uint32_t number, char *path, size_t size,
                              fc_error *err);

/* Whether frame `number`'s image file exists already (false for a video). */
bool fc_render_output_exists(const fc_render_output *out, uint32_t number);

/* Writes frame `number`'s image: appends it to the video or writes its file.
 * FC_ERR_PROTOCOL for RAW bytes of the wrong size, FC_ERR_IO naming the file. */
fc_code fc_render_output_write(fc_render_output *out, uint32_t number, const fc_image_result *image,
                               fc_error *err);

/* Finishes the video (flush and trailer: what was written plays); nothing
 * for images. */
fc_code fc_render_output_close(fc_render_output *out, fc_error *err);

#endif
