/* h264_encoder.c — see h264_encoder.h. */
#include "h264_encoder.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include <libavcodec/avcodec.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>

#include "fc_error.h"

/* Frames between periodic IDR frames: a stream also recovers on its own from
 * a lost access unit within this many frames; key frames on demand (join,
 * missed frames, resize) come on top of them. */
enum { GOP_FRAMES = 300 };

struct fc_h264_encoder {
    AVCodecContext *codec;
    struct SwsContext *scale;
    AVFrame *frame;
    AVPacket *packet;
    uint32_t width, height;
    int64_t frames;
};

uint32_t fc_h264_crf_for_quality(uint32_t quality)
{
    if (quality < 1)
        quality = 1;
    if (quality > 100)
        quality = 100;
    return (uint32_t)(51.0 - 0.31 * (double)quality + 0.5);
}

uint64_t fc_h264_encoder_memory(uint32_t width, uint32_t height)
{
    enum { BYTES_PER_PIXEL = 24, FIXED_BYTES = 4 << 20 };
    return (uint64_t)BYTES_PER_PIXEL * width * height + FIXED_BYTES;
}

static fc_code av_failure(fc_error *err, const char *what, int averr)
{
    char reason[AV_ERROR_MAX_STRING_SIZE];
    av_strerror(averr, reason, sizeof reason);
    return fc_error_set(err, FC_ERR_ENCODE, "H.264: %s: %s", what, reason);
}

/* Latency first: every frame goes out as soon as it is encoded. */
static void set_low_latency(AVCodecContext *ctx, uint32_t quality)
{
    av_opt_set(ctx->priv_data, "preset", "veryfast", 0);
    av_opt_set(ctx->priv_data, "tune", "zerolatency", 0);   /* no lookahead, no frame threads, no B-frames */
    av_opt_set_int(ctx->priv_data, "crf", fc_h264_crf_for_quality(quality), 0);
    av_opt_set_int(ctx->priv_data, "forced-idr", 1, 0);     /* a forced key frame is an IDR, not an open I */
    ctx->max_b_frames = 0;
    ctx->gop_size = GOP_FRAMES;
    /* One thread per stream: the encoder pool runs streams in parallel. */
    ctx->thread_count = 1;
    /* x264 reports its statistics at INFO through av_log; one step quieter
     * keeps them out of the daemon's log without touching libav's global level. */
    ctx->log_level_offset = AV_LOG_VERBOSE - AV_LOG_INFO;
}

static fc_code open_codec(fc_h264_encoder *enc, uint32_t quality, fc_error *err)
{
    const AVCodec *codec = avcodec_find_encoder_by_name("libx264");
    if (!codec)
        return fc_error_set(err, FC_ERR_ENCODE, "H.264: this libavcodec has no libx264 encoder");
    enc->codec = avcodec_alloc_context3(codec);
    if (!enc->codec)
        return fc_error_set(err, FC_ERR_NOMEM, "H.264: no memory for the encoder");
    AVCodecContext *ctx = enc->codec;
    ctx->width = (int)enc->width;
    ctx->height = (int)enc->height;
    ctx->time_base = (AVRational){1, 60};
    ctx->pix_fmt = AV_PIX_FMT_YUV420P;
    /* libswscale's default matrix, said in the stream so decoders invert it. */
    ctx->colorspace = AVCOL_SPC_SMPTE170M;
    ctx->color_primaries = AVCOL_PRI_BT709;
    ctx->color_trc = AVCOL_TRC_IEC61966_2_1;
    ctx->color_range = AVCOL_RANGE_MPEG;
    set_low_latency(ctx, quality);
    int rc = avcodec_open2(ctx, codec, NULL);
    return rc < 0 ? av_failure(err, "cannot open libx264", rc) : FC_OK;
}

static fc_code alloc_pictures(fc_h264_encoder *enc, fc_error *err)
{
    int w = (int)enc->width, h = (int)enc->height;
    enc->frame = av_frame_alloc();
    enc->packet = av_packet_alloc();
    enc->scale = sws_getContext(w, h, AV_PIX_FMT_RGBA, w, h, AV_PIX_FMT_YUV420P, SWS_BILINEAR, NULL, NULL, NULL);
    if (!enc->frame || !enc->packet || !enc->scale)
        return fc_error_set(err, FC_ERR_NOMEM, "H.264: no memory for %dx%d pictures", w, h);
    enc->frame->format = AV_PIX_FMT_YUV420P;
    enc->frame->width = w;
    enc->frame->height = h;
    int rc = av_frame_get_buffer(enc->frame, 0);
    return rc < 0 ? av_failure(err, "no picture buffer", rc) : FC_OK;
}

fc_code fc_h264_encoder_create(uint32_t width, uint32_t height, uint32_t quality, fc_h264_encoder **out,
                               fc_error *err)
{
    *out = NULL;
    if (width == 0 || height == 0 || width % 2 || height % 2)
        return fc_error_set(err, FC_ERR_ENCODE, "H.264 needs an even width and height (4:2:0), not %ux%u",
                            (unsigned)width, (unsigned)height);
    fc_h264_encoder *enc = calloc(1, sizeof *enc);
    if (!enc)
        return fc_error_set(err, FC_ERR_NOMEM, "H.264: no memory for the encoder");
    enc->width = width;
    enc->height = height;
    fc_code code = open_codec(enc, quality, err);
    if (code == FC_OK)
        code = alloc_pictures(enc, err);
    if (code != FC_OK) {
        fc_h264_encoder_free(enc);
        return code;
    }
    *out = enc;
    return FC_OK;
}

void fc_h264_encoder_free(fc_h264_encoder *enc)
{
    if (!enc)
        return;
    avcodec_free_context(&enc->codec);
    sws_freeContext(enc->scale);
    av_frame_free(&enc->frame);
    av_packet_free(&enc->packet);
    free(enc);
}

uint32_t fc_h264_encoder_width(const fc_h264_encoder *enc)
{
    return enc->width;
}

uint32_t fc_h264_encoder_height(const fc_h264_encoder *enc)
{
    return enc->height;
}

static fc_code check_image(const fc_h264_encoder *enc, const fc_image *img, fc_error *err)
{
    if (img->type != FC_PIXEL_U8 || img->channels != 4)
        return fc_error_set(err, FC_ERR_ENCODE, "H.264 encodes 8-bit RGBA colour only");
    if (img->width != enc->width || img->height != enc->height)
        return fc_error_set(err, FC_ERR_ENCODE, "H.264: a %ux%u image for a %ux%u stream", (unsigned)img->width,
                            (unsigned)img->height, (unsigned)enc->width, (unsigned)enc->height);
    return FC_OK;
}

/* The picture to encode: img in yuv420p. */
static fc_code fill_frame(fc_h264_encoder *enc, const fc_image *img, bool force_keyframe, fc_error *err)
{
    int rc = av_frame_make_writable(enc->frame);
    if (rc < 0)
        return av_failure(err, "no picture buffer", rc);
    const uint8_t *const src[1] = {img->pixels};
    const int stride[1] = {4 * (int)img->width};
    sws_scale(enc->scale, src, stride, 0, (int)img->height, enc->frame->data, enc->frame->linesize);
    enc->frame->pts = enc->frames;
    enc->frame->pict_type = force_keyframe ? AV_PICTURE_TYPE_I : AV_PICTURE_TYPE_NONE;
    return FC_OK;
}

fc_code fc_h264_encoder_encode(fc_h264_encoder *enc, const fc_image *img, bool force_keyframe, fc_buf *out,
                               bool *keyframe, fc_error *err)
{
    *keyframe = false;
    fc_code code = check_image(enc, img, err);
    if (code == FC_OK)
        code = fill_frame(enc, img, force_keyframe, err);
    if (code != FC_OK)
        return code;
    int rc = avcodec_send_frame(enc->codec, enc->frame);
    if (rc < 0)
        return av_failure(err, "cannot encode a frame", rc);
    rc = avcodec_receive_packet(enc->codec, enc->packet);
    /* Without lookahead or B-frames every frame comes straight back; a held
     * one would break the one-image-per-frame stream. */
    if (rc == AVERROR(EAGAIN))
        return fc_error_set(err, FC_ERR_ENCODE, "H.264: the encoder held a frame back");
    if (rc < 0)
        return av_failure(err, "cannot encode a frame", rc);
    enc->frames++;
    *keyframe = (enc->packet->flags & AV_PKT_FLAG_KEY) != 0;
    size_t n = (size_t)enc->packet->size;
    bool room = fc_buf_reserve(out, n);
    if (room) {
        memcpy(out->data + out->len, enc->packet->data, n);
        out->len += n;
    }
    av_packet_unref(enc->packet);
    return room ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "H.264: no memory for an access unit");
}
