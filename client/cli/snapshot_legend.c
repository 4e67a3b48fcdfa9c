/* snapshot_legend.c — see snapshot_legend.h. */
#include "snapshot_legend.h"

#include <stdlib.h>

#include "cli_module.h"
#include "fc_error.h"
#include "image_module.h"
#include "wire.h"

#ifndef FC_LEGEND_FONT
#define FC_LEGEND_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif
/* The server's images are at most this many pixels per side (its --max-image). */
#define MAX_SIDE 65536u

/* Decoded, drawn on, encoded again into *encoded with the image codecs of `codecs`. */
static fc_code redraw(const fc_image_module *codecs, const fc_image_result *image, const fc_settings *settings,
                      uint32_t quality, fc_legend_box *box, fc_buf *encoded, fc_error *err)
{
    fc_image decoded = {0};
    fc_code code = codecs->decode(image->data, image->size, MAX_SIDE, &decoded, err);
    if (code == FC_OK)
        code = fc_legend_draw(&decoded, settings, FC_LEGEND_FONT, box, err);
    if (code == FC_OK)
        code = codecs->encode(&decoded, image->format, quality, encoded, err);
    free(decoded.pixels);   /* fc_image_free lives in the renderer's library */
    return code;
}

fc_code fc_snapshot_add_legend(fc_image_result *image, const fc_settings *settings, uint32_t quality,
                               fc_legend_box *box, fc_error *err)
{
    /* OpenImageIO is loaded here, for the legend only (cli_module.h). */
    fc_cli_module module;
    fc_code code = fc_cli_module_open(FC_IMAGE_MODULE_FILE, FC_IMAGE_MODULE_SYMBOL, FC_IMAGE_MODULE_ABI,
                                      "--legend", &module, err);
    if (code != FC_OK)
        return code;
    fc_buf encoded;
    fc_buf_init(&encoded);
    code = redraw(module.api, image, settings, quality, box, &encoded, err);
    fc_cli_module_close(&module);
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
