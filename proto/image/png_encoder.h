/* png_encoder.h — PNG files of 8-bit grey, RGB or RGBA rows, written by
 * fluidcast itself so that the deflating runs on several threads
 * (png_strips.h); the container is the PNG specification's few chunks, the
 * compression stays zlib's. */
#ifndef FC_PNG_ENCODER_H
#define FC_PNG_ENCODER_H

#include "png_strips.h"
#include "wire.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Appends a PNG of `rows` (1 channel: grey, 3: RGB, 4: RGBA with straight
 * alpha; 8 bits) to `out`: IHDR, an oFFs of (0, 0) pixels (what OpenImageIO's
 * writer put there before), the image data as IDAT chunks (one per strip),
 * IEND. Rows are SUB-filtered (none at level 0) and deflated at zlib `level`
 * 0..9 on `threads` threads (0: automatic, png_strips.h); the bytes do not
 * depend on the thread count. FC_ERR_USAGE for a level, size or channel count
 * PNG cannot hold, FC_ERR_NOMEM, FC_ERR_ENCODE; out->len is unchanged then. */
fc_code fc_png_encode(const fc_png_rows *rows, uint32_t level, unsigned threads, fc_buf *out, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
