/* image_encoder.h — in-memory image encoding: PNG by fluidcast's own writer
 * (png_encoder.h: zlib in strips on several threads), JPEG and EXR with
 * OpenImageIO through an IOProxy; no temporary files. C interface over
 * image_encoder.cpp. */
#ifndef FC_IMAGE_ENCODER_H
#define FC_IMAGE_ENCODER_H

#include "fluidcast_types.h"
#include "wire.h"
#include "image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* PNG's zlib level when none is chosen. With the SUB row filter, level 4
 * encoded a rendered 1280x720 RGBA image about 3.5 times faster than
 * OpenImageIO's default (level 6, libpng's adaptive filters) into a file
 * about 4% larger, on one core; png_encoder.h spreads it over several. An
 * opaque colour image is written as RGB, and at level 2 its file is as
 * large as the RGBA one at level 4 and takes 40% less time (bench/RESULTS.md,
 * "PNG as RGB"). */
#define FC_PNG_DEFAULT_COMPRESSION 2   /* unsuffixed: fluidcastd --help prints it (FC_STRINGIFY) */
#define FC_PNG_MAX_COMPRESSION 9u

/* Encodes img into `out` (appended after out->len) in `format`:
 *   PNG:  U8 RGBA/1-channel as is; F32 converted (colour clamped to [0,1] and sRGB-encoded);
 *         zlib level FC_PNG_DEFAULT_COMPRESSION, SUB filter, deflated in strips on up to
 *         FC_PNG_MAX_THREADS threads (png_encoder.h); 1 channel: grey, 3: RGB, 4: RGBA, or RGB
 *         where every pixel's alpha is 255 (the alpha left out).
 *   JPEG: like PNG, alpha dropped, `quality` 1..100, chroma 4:4:4 (baseline, libjpeg-turbo's
 *         accurate integer DCT and standard Huffman tables: the fastest settings that keep quality).
 *   EXR:  F32 as float32 channels (R,G,B,A; R,G,B for the normal AOV; a single "Z" channel for the
 *         other AOVs); U8 converted to float.
 *   RAW:  the pixel rows as they are.
 * H.264 is a stream, not a file: h264_encoder.h (FC_ERR_USAGE here).
 * FC_ERR_ENCODE with OpenImageIO's (or zlib's) message on failure. */
fc_code fc_encode_image(const fc_image *img, fc_image_format format, uint32_t quality,
                        fc_buf *out, fc_error *err);

/* fc_encode_image with PNG's zlib level chosen: 0 (stored: fastest, about the
 * size of the pixels) .. 9 (smallest, slowest); rows use the SUB filter (none
 * at level 0). Other formats ignore it. FC_ERR_USAGE above 9. */
fc_code fc_encode_image_png_level(const fc_image *img, fc_image_format format, uint32_t quality,
                                  uint32_t png_compression, fc_buf *out, fc_error *err);

/* How to encode, beyond the format: the choices a request or the daemon makes. */
typedef struct fc_encode_options {
    uint32_t quality;                     /* JPEG 1..100 */
    uint32_t png_compression;             /* PNG's zlib level 0..9 */
    fc_jpeg_subsampling jpeg_subsampling; /* JPEG chroma: 4:4:4 or 4:2:0 (libjpeg-turbo's 2x2 luma blocks) */
} fc_encode_options;

/* fc_encode_image with every choice explicit. FC_ERR_USAGE for a choice out of range. */
fc_code fc_encode_image_with(const fc_image *img, fc_image_format format, const fc_encode_options *options,
                             fc_buf *out, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
