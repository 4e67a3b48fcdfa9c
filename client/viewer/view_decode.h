/* view_decode.h — the viewer's image decoder, on the network worker's thread:
 * RAW RGBA8 taken as it is; H.264 access units fed in order to one libavcodec
 * decoder (a stream's, or a RENDER's IDR frames of their own); JPEG and the
 * PNG refreshes of a lossy stream decoded with libavcodec too. Every picture
 * comes out as RGBA8 rows, top to bottom (libswscale, with the matrix and
 * range the stream says). */
#ifndef FC_VIEW_DECODE_H
#define FC_VIEW_DECODE_H

#include "fluidcast.h"
#include "view_slot.h"

typedef struct fc_view_decoder fc_view_decoder;

fc_code fc_view_decoder_create(fc_view_decoder **out, fc_error *err);
/* NULL is ignored. */
void fc_view_decoder_free(fc_view_decoder *d);

/* Decodes img into out->rgba, width and height (and copies its stage
 * timings); RAW data is taken over (img->data becomes NULL). FC_ERR_PROTOCOL
 * for an image that does not decode or a format the viewer does not show
 * (EXR). An H.264 access unit before the stream's first key frame yields no
 * picture: FC_OK with out->rgba NULL. */
fc_code fc_view_decoder_decode(fc_view_decoder *d, fc_image_result *img, fc_view_image *out, fc_error *err);

#endif
