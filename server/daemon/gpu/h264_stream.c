/* h264_stream.c — see h264_stream.h. */
#include "gpu/h264_stream.h"

#include <stdatomic.h>
#include <stdlib.h>

#include "encode/h264_encoder.h"

struct fc_h264_stream {
    atomic_uint refs;
    uint32_t quality;
    fc_h264_encoder *encoder;    /* NULL until the first image, and after a failure */
};

uint64_t fc_h264_stream_memory(uint32_t width, uint32_t height)
{
    return fc_h264_encoder_memory(width, height);
}

fc_h264_stream *fc_h264_stream_create(uint32_t quality)
{
    fc_h264_stream *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    atomic_init(&s->refs, 1);
    s->quality = quality;
    return s;
}

fc_h264_stream *fc_h264_stream_ref(fc_h264_stream *s)
{
    atomic_fetch_add_explicit(&s->refs, 1, memory_order_relaxed);
    return s;
}

void fc_h264_stream_unref(fc_h264_stream *s)
{
    if (!s || atomic_fetch_sub_explicit(&s->refs, 1, memory_order_acq_rel) != 1)
        return;
    fc_h264_encoder_free(s->encoder);
    free(s);
}

/* An encoder for img's size: the current one, or a new one (the stream restarts). */
static fc_code encoder_for(fc_h264_stream *s, const fc_image *img, bool *fresh, fc_error *err)
{
    *fresh = false;
    if (s->encoder && fc_h264_encoder_width(s->encoder) == img->width &&
        fc_h264_encoder_height(s->encoder) == img->height)
        return FC_OK;
    fc_h264_encoder_free(s->encoder);
    s->encoder = NULL;
    *fresh = true;
    return fc_h264_encoder_create(img->width, img->height, s->quality, &s->encoder, err);
}

fc_code fc_h264_stream_encode(fc_h264_stream *s, const fc_image *img, bool force_keyframe, fc_buf *out,
                              bool *keyframe, fc_error *err)
{
    *keyframe = false;
    bool fresh;
    fc_code code = encoder_for(s, img, &fresh, err);
    if (code == FC_OK)
        code = fc_h264_encoder_encode(s->encoder, img, force_keyframe || fresh, out, keyframe, err);
    if (code != FC_OK) {
        fc_h264_encoder_free(s->encoder);
        s->encoder = NULL;
    }
    return code;
}

fc_code fc_h264_encode_single(const fc_image *img, uint32_t quality, fc_buf *out, fc_error *err)
{
    fc_h264_encoder *enc;
    fc_code code = fc_h264_encoder_create(img->width, img->height, quality, &enc, err);
    if (code != FC_OK)
        return code;
    bool keyframe;
    code = fc_h264_encoder_encode(enc, img, true, out, &keyframe, err);
    fc_h264_encoder_free(enc);
    return code;
}
