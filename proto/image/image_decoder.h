/* image_decoder.h — decoding a client's image file (PNG, JPEG or EXR) from
 * memory with OpenImageIO through an IOProxy: no temporary files. C interface
 * over image_decoder.cpp; the daemon turns scene images into textures with it. */
#ifndef FC_IMAGE_DECODER_H
#define FC_IMAGE_DECODER_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Decodes the `size` bytes of one PNG, JPEG or EXR file into *out, which is
 * overwritten (free the result with free(out->pixels) or fc_image_free). The result is always RGBA: grey becomes R = G = B, a missing
 * alpha is opaque, channels past the fourth are dropped. Integer files give
 * FC_PIXEL_U8 samples as stored (sRGB-encoded, straight alpha); float and half
 * files (EXR) give FC_PIXEL_F32, linear.
 * Errors: FC_ERR_INVALID_VALUE when the bytes are not a complete PNG, JPEG or
 * EXR image (message says why), FC_ERR_LIMIT when a side exceeds max_side,
 * FC_ERR_NOMEM. On failure *out is empty. */
fc_code fc_decode_image_bytes(const uint8_t *data, size_t size, uint32_t max_side, fc_image *out, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
