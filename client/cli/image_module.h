/* image_module.h — the interface of fluidcast-image.so (modules/image_module.c):
 * image files decoded and encoded with OpenImageIO, for --legend. The command
 * opens it with fc_cli_module_open (cli_module.h) only when it needs it, so
 * OpenImageIO's libraries are not loaded by anything else. */
#ifndef FC_IMAGE_MODULE_H
#define FC_IMAGE_MODULE_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "image.h"
#include "wire.h"

#define FC_IMAGE_MODULE_FILE "fluidcast-image.so"
#define FC_IMAGE_MODULE_SYMBOL "fc_image_module_v1"
/* Raised whenever the struct below changes. */
#define FC_IMAGE_MODULE_ABI 1u

typedef struct fc_image_module {
    uint32_t abi;   /* FC_IMAGE_MODULE_ABI: first, checked when the module is opened */
    /* fc_decode_image_bytes (proto/image/image_decoder.h): a PNG, JPEG or EXR
     * file's bytes into RGBA; free the pixels with free(). */
    fc_code (*decode)(const uint8_t *data, size_t size, uint32_t max_side, fc_image *out, fc_error *err);
    /* fc_encode_image (proto/image/image_encoder.h): appended to `out`. */
    fc_code (*encode)(const fc_image *img, fc_image_format format, uint32_t quality, fc_buf *out, fc_error *err);
} fc_image_module;

#endif
