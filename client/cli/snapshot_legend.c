/* snapshot_legend.c — see snapshot_legend.h. */
#include "snapshot_legend.h"

#include <stdlib.h>

#include "fc_error.h"
#include "image_decoder.h"
#include "image_encoder.h"
#include "wire.h"

#ifndef FC_LEGEND_FONT
#define FC_LEGEND_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif
/* The server's images are at most this many pixels per side (its --max-image). */
#define MAX_SIDE 65536u

fc_code fc_snapshot_add_legend(fc_image_result *image, const fc_settings *settings, uint32_t quality,
                               fc_legend_box *box, fc_error *err)
{
    fc_image decoded = {0};
    fc_code code = fc_decode_image_bytes(image->data, image->size, MAX_SIDE, &decoded, err);
    if (code == FC_OK)
        code = fc_legend_draw(&decoded, settings, FC_LEGEND_FONT, box, err);
    fc_buf encoded;
    fc_buf_init(&encoded);
    if (code == FC_OK)
        code = fc_encode_image(&decoded, image->format, quality, &encoded, err);
    free(decoded.pixels);   /* fc_image_free lives in the renderer's library */
    if (code != FC_OK) {
        fc_buf_free(&encoded);
        return code;
    }
    /* The buffer's bytes become the result's, which fc_image_result_free frees. */
    free(image->data);
    image->data = encoded.data;
    image->size = encoded.len;
    return FC_OK;
}
