/* image_encoder.h — in-memory image encoding with OpenImageIO (PNG, JPEG, EXR)
 * through an IOProxy: no temporary files. C interface over image_encoder.cpp. */
#ifndef FC_IMAGE_ENCODER_H
#define FC_IMAGE_ENCODER_H

#include "fluidcast_types.h"
#include "wire.h"
#include "../image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Encodes img into `out` (appended after out->len) in `format`:
 *   PNG:  U8 RGBA/1-channel as is; F32 converted (colour clamped to [0,1] and sRGB-encoded).
 *   JPEG: like PNG, alpha dropped, `quality` 1..100.
 *   EXR:  F32 as float32 channels (R,G,B,A; R,G,B for the normal AOV; a single "Z" channel for the
 *         other AOVs); U8 converted to float.
 *   RAW:  the pixel rows as they are.
 * FC_ERR_ENCODE with OpenImageIO's message on failure. */
fc_code fc_encode_image(const fc_image *img, fc_image_format format, uint32_t quality,
                        fc_buf *out, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
