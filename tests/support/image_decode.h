/* image_decode.h — decodes an encoded image from memory with OpenImageIO, so
 * tests can check what the encoder and the daemon produced without trusting
 * the code under test. C interface over image_decode.cpp. */
#ifndef FC_TEST_IMAGE_DECODE_H
#define FC_TEST_IMAGE_DECODE_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fc_decoded_image {
    uint32_t width;
    uint32_t height;
    uint32_t channels;
    char channel_names[4][16];
    char compression[32];  /* the file's "compression" attribute, e.g. "zip" for EXR */
    int as_float;      /* pixels are float when nonzero, else uint8 */
    void *pixels;      /* rows top to bottom, channels interleaved; free with fc_decoded_image_free */
} fc_decoded_image;

/* Decodes `size` bytes as the file format `extension` names ("png", "jpg",
 * "exr"), converting samples to float (as_float) or uint8. FC_ERR_PARSE with
 * OpenImageIO's message when the bytes are not such a file. */
fc_code fc_decode_image(const uint8_t *data, size_t size, const char *extension, int as_float,
                        fc_decoded_image *out, fc_error *err);
void fc_decoded_image_free(fc_decoded_image *img);

#ifdef __cplusplus
}
#endif
#endif
