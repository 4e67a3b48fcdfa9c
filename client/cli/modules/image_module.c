/* image_module.c — fluidcast-image.so: the image codecs behind image_module.h.
 * The only symbol it exports is the interface; OpenImageIO comes with it. */
#include "image_module.h"

#include "image_decoder.h"
#include "image_encoder.h"

__attribute__((visibility("default"))) extern const fc_image_module fc_image_module_v1;

const fc_image_module fc_image_module_v1 = {
    .abi = FC_IMAGE_MODULE_ABI,
    .decode = fc_decode_image_bytes,
    .encode = fc_encode_image,
};
