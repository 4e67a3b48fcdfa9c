/* render_writer.h — writes `fluidcast render`'s images (appends them to the
 * video, encoding them, or writes their files) on a thread of its own, at
 * most two images behind the connection, so that the server renders frame
 * i + 1 while frame i is encoded and written: neither the daemon nor the
 * connection waits for the encoder or the disk. Images are written in the
 * order they are put; after the first failure nothing more is written. */
#ifndef FC_RENDER_WRITER_H
#define FC_RENDER_WRITER_H

#include <stdint.h>

#include "fluidcast.h"
#include "render_output.h"

#define FC_RENDER_WRITE_BEHIND 2

typedef struct fc_render_writer fc_render_writer;

/* Starts the thread that writes to `output` (opened; it must outlive the
 * writer). FC_ERR_NOMEM or FC_ERR_IO when the thread cannot be made. */
fc_code fc_render_writer_start(fc_render_output *output, fc_render_writer **out, fc_error *err);

/* Queues frame `number`'s image, waiting while FC_RENDER_WRITE_BEHIND are
 * queued; the image's bytes move to the writer (*image is emptied either
 * way). Returns the writer's first failure, if it had one (then the image is
 * freed, not written): the codes of fc_render_output_write. */
fc_code fc_render_writer_put(fc_render_writer *w, uint32_t number, fc_image_result *image, fc_error *err);

/* Writes what is queued, stops the thread and frees the writer; *written
 * gets the number of images written. Returns the first failure, as put. */
fc_code fc_render_writer_finish(fc_render_writer *w, uint32_t *written, fc_error *err);

#endif
