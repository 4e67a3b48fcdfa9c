/* view_decode.c — see view_decode.h. */
#include "view_decode.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include <libavcodec/avcodec.h>
#include <libswscale/swscale.h>

#include "fc_error.h"

struct fc_view_decoder {
    AVCodecContext *h264;         /* the stream's decoder: its reference frames live across calls */
    AVCodecContext *jpeg, *png;   /* made on first use */
    AVPacket *packet;
    AVFrame *frame;
    struct SwsContext *scale;     /* cached for the last size and pixel format */
};

static fc_code open_decoder(enum AVCodecID id, AVCodecContext **out, fc_error *err)
{
    const AVCodec *codec = avcodec_find_decoder(id);
    if (!codec)
        return fc_error_set(err, FC_ERR_IO, "this libavcodec has no %s decoder", avcodec_get_name(id));
    AVCodecContext *ctx = avcodec_alloc_context3(codec);
    if (!ctx)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the %s decoder", codec->name);
    /* Each access unit out as soon as it is in: the stream has no B-frames. */
    ctx->flags |= AV_CODEC_FLAG_LOW_DELAY;
    ctx->thread_count = 1;
    if (avcodec_open2(ctx, codec, NULL) < 0) {
        avcodec_free_context(&ctx);
        return fc_error_set(err, FC_ERR_IO, "cannot open the %s decoder", codec->name);
    }
    *out = ctx;
    return FC_OK;
}

fc_code fc_view_decoder_create(fc_view_decoder **out, fc_error *err)
{
    *out = NULL;
    fc_view_decoder *d = calloc(1, sizeof *d);
    if (!d)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the image decoder");
    d->packet = av_packet_alloc();
    d->frame = av_frame_alloc();
    fc_code code = d->packet && d->frame ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "no memory for the decoder");
    if (code == FC_OK)
        code = open_decoder(AV_CODEC_ID_H264, &d->h264, err);
    if (code != FC_OK) {
        fc_view_decoder_free(d);
        return code;
    }
    *out = d;
    return FC_OK;
}

void fc_view_decoder_free(fc_view_decoder *d)
{
    if (!d)
        return;
    avcodec_free_context(&d->h264);
    avcodec_free_context(&d->jpeg);
    avcodec_free_context(&d->png);
    av_packet_free(&d->packet);
    av_frame_free(&d->frame);
    sws_freeContext(d->scale);
    free(d);
}

/* The decoded picture as RGBA8 rows. */
static fc_code to_rgba(fc_view_decoder *d, fc_view_image *out, fc_error *err)
{
    const AVFrame *f = d->frame;
    d->scale = sws_getCachedContext(d->scale, f->width, f->height, f->format, f->width, f->height,
                                    AV_PIX_FMT_RGBA, SWS_BILINEAR, NULL, NULL, NULL);
    out->rgba = malloc((size_t)f->width * (size_t)f->height * 4u);
    if (!d->scale || !out->rgba) {
        free(out->rgba);
        out->rgba = NULL;
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %dx%d picture", f->width, f->height);
    }
    uint8_t *dst[1] = {out->rgba};
    int stride[1] = {4 * f->width};
    sws_scale(d->scale, (const uint8_t *const *)f->data, f->linesize, 0, f->height, dst, stride);
    out->width = (uint32_t)f->width;
    out->height = (uint32_t)f->height;
    return FC_OK;
}

/* One packet through `ctx`; *got: whether a picture came out. */
static fc_code run_decoder(fc_view_decoder *d, AVCodecContext *ctx, const fc_image_result *img, bool *got,
                           fc_error *err)
{
    *got = false;
    if (img->size > INT32_MAX || av_new_packet(d->packet, (int)img->size) < 0)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %zu-byte image", img->size);
    memcpy(d->packet->data, img->data, img->size);
    int rc = avcodec_send_packet(ctx, d->packet);
    av_packet_unref(d->packet);
    if (rc >= 0)
        rc = avcodec_receive_frame(ctx, d->frame);
    if (rc == AVERROR(EAGAIN))
        return FC_OK;
    if (rc < 0)
        return fc_error_set(err, FC_ERR_PROTOCOL, "a %s image from the server does not decode", ctx->codec->name);
    *got = true;
    return FC_OK;
}

static fc_code decode_coded(fc_view_decoder *d, const fc_image_result *img, fc_view_image *out, fc_error *err)
{
    AVCodecContext **ctx = img->format == FC_FORMAT_H264 ? &d->h264 : img->format == FC_FORMAT_JPEG ? &d->jpeg : &d->png;
    enum AVCodecID id = img->format == FC_FORMAT_JPEG ? AV_CODEC_ID_MJPEG : AV_CODEC_ID_PNG;
    fc_code code = *ctx ? FC_OK : open_decoder(id, ctx, err);
    bool got = false;
    if (code == FC_OK)
        code = run_decoder(d, *ctx, img, &got, err);
    /* An access unit that refers to one the decoder never had (before the
     * stream's first key frame, after a lost one) shows nothing until an IDR. */
    if (code == FC_ERR_PROTOCOL && img->format == FC_FORMAT_H264)
        return FC_OK;
    if (code == FC_OK && got)
        code = to_rgba(d, out, err);
    av_frame_unref(d->frame);
    return code;
}

fc_code fc_view_decoder_decode(fc_view_decoder *d, fc_image_result *img, fc_view_image *out, fc_error *err)
{
    out->rgba = NULL;
    memcpy(out->stage_ms, img->stage_ms, sizeof out->stage_ms);
    switch (img->format) {
    case FC_FORMAT_RAW:
        /* RAW colour is RGBA8 rows, top to bottom: decoding is checking the size. */
        if (img->size != (size_t)img->width * img->height * 4u)
            return fc_error_set(err, FC_ERR_PROTOCOL, "expected %ux%u RGBA8, got %zu bytes", (unsigned)img->width,
                                (unsigned)img->height, img->size);
        out->rgba = img->data;
        out->width = img->width;
        out->height = img->height;
        img->data = NULL;
        img->size = 0;
        return FC_OK;
    case FC_FORMAT_H264:
    case FC_FORMAT_JPEG:
    case FC_FORMAT_PNG:
        return decode_coded(d, img, out, err);
    case FC_FORMAT_EXR:
        break;
    }
    return fc_error_set(err, FC_ERR_PROTOCOL, "the viewer does not show format %d images", (int)img->format);
}
