/* video_module.c — fluidcast-video.so: video files through libavcodec,
 * libavformat and libswscale, behind video_module.h. The only symbol it
 * exports is the interface; libav comes with it. */
#include "video_module.h"

#include <stdlib.h>
#include <string.h>

#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>

#include "fc_error.h"

struct fc_video_file {
    AVFormatContext *format;
    AVCodecContext *codec;
    AVStream *stream;
    struct SwsContext *scale;
    AVFrame *frame;
    AVPacket *packet;
    const char *codec_name;
    int64_t frames;
    char path[1024];
};

static fc_code av_failure(fc_error *err, const char *what, const char *path, int averr)
{
    char reason[AV_ERROR_MAX_STRING_SIZE];
    av_strerror(averr, reason, sizeof reason);
    return fc_error_set(err, FC_ERR_IO, "%s %s: %s", what, path, reason);
}

/* The first candidate libavcodec has. */
static const AVCodec *find_encoder(const fc_video_file_params *p, fc_error *err)
{
    for (size_t i = 0; i < p->encoder_count; i++) {
        const AVCodec *codec = avcodec_find_encoder_by_name(p->encoders[i]);
        if (codec)
            return codec;
    }
    fc_error_set(err, FC_ERR_IO, "this libavcodec has no encoder for %s (tried %s%s%s)", p->path,
                 p->encoder_count ? p->encoders[0] : "none", p->encoder_count > 1 ? " and " : "",
                 p->encoder_count > 1 ? p->encoders[p->encoder_count - 1] : "");
    return NULL;
}

/* Constant quality: x264's and VP9's crf; MPEG-4's fixed quantiser 2..31. */
static void set_quality(AVCodecContext *ctx, const char *encoder, uint32_t crf)
{
    if (strcmp(encoder, "mpeg4") == 0) {
        ctx->flags |= AV_CODEC_FLAG_QSCALE;
        ctx->global_quality = FF_QP2LAMBDA * (int)(2 + crf * 29 / 51);
        return;
    }
    av_opt_set_int(ctx->priv_data, "crf", crf, 0);
    if (strcmp(encoder, "libvpx-vp9") == 0) {
        ctx->bit_rate = 0;   /* crf alone: constant quality */
        av_opt_set_int(ctx->priv_data, "row-mt", 1, 0);
        av_opt_set_int(ctx->priv_data, "cpu-used", 4, 0);   /* "good" deadline, faster */
    }
}

static fc_code open_codec(fc_video_file *v, const AVCodec *codec, const fc_video_file_params *p, fc_error *err)
{
    v->codec = avcodec_alloc_context3(codec);
    if (!v->codec)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the %s encoder", codec->name);
    v->codec->width = (int)p->width;
    v->codec->height = (int)p->height;
    v->codec->time_base = (AVRational){1, (int)p->fps};
    v->codec->framerate = (AVRational){(int)p->fps, 1};
    v->codec->pix_fmt = AV_PIX_FMT_YUV420P;
    v->codec->gop_size = (int)(p->fps < 250 ? 2 * p->fps : 250);
    if (v->format->oformat->flags & AVFMT_GLOBALHEADER)
        v->codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    set_quality(v->codec, codec->name, p->quality);
    int rc = avcodec_open2(v->codec, codec, NULL);
    if (rc < 0)
        return av_failure(err, "cannot open the encoder for", v->path, rc);
    v->codec_name = codec->name;
    v->stream = avformat_new_stream(v->format, NULL);
    if (!v->stream)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the video stream");
    v->stream->time_base = v->codec->time_base;
    rc = avcodec_parameters_from_context(v->stream->codecpar, v->codec);
    return rc < 0 ? av_failure(err, "cannot describe the stream of", v->path, rc) : FC_OK;
}

static fc_code alloc_pictures(fc_video_file *v, const fc_video_file_params *p, fc_error *err)
{
    v->frame = av_frame_alloc();
    v->packet = av_packet_alloc();
    v->scale = sws_getContext((int)p->width, (int)p->height, AV_PIX_FMT_RGBA, (int)p->width, (int)p->height,
                              AV_PIX_FMT_YUV420P, SWS_BICUBIC, NULL, NULL, NULL);
    if (!v->frame || !v->packet || !v->scale)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the video frames");
    v->frame->format = AV_PIX_FMT_YUV420P;
    v->frame->width = (int)p->width;
    v->frame->height = (int)p->height;
    int rc = av_frame_get_buffer(v->frame, 0);
    return rc < 0 ? av_failure(err, "no picture buffer for", v->path, rc) : FC_OK;
}

static fc_code open_file(fc_video_file *v, fc_error *err)
{
    int rc = avio_open(&v->format->pb, v->path, AVIO_FLAG_WRITE);
    if (rc < 0)
        return av_failure(err, "cannot write", v->path, rc);
    rc = avformat_write_header(v->format, NULL);
    return rc < 0 ? av_failure(err, "cannot write the header of", v->path, rc) : FC_OK;
}

static void free_encoder(fc_video_file *v)
{
    if (v->format && v->format->pb)
        avio_closep(&v->format->pb);
    avformat_free_context(v->format);
    avcodec_free_context(&v->codec);
    sws_freeContext(v->scale);
    av_frame_free(&v->frame);
    av_packet_free(&v->packet);
    free(v);
}

static fc_code video_open(const fc_video_file_params *params, fc_video_file **out, fc_error *err)
{
    *out = NULL;
    if (strlen(params->path) >= sizeof ((fc_video_file *)0)->path)
        return fc_error_set(err, FC_ERR_USAGE, "the video path is too long");
    const AVCodec *codec = find_encoder(params, err);
    if (!codec)
        return FC_ERR_IO;
    av_log_set_level(AV_LOG_ERROR);   /* libav's log is process-wide; x264 prints statistics at INFO */
    fc_video_file *v = calloc(1, sizeof *v);
    if (!v)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the video encoder");
    strcpy(v->path, params->path);
    int rc = avformat_alloc_output_context2(&v->format, NULL, NULL, v->path);
    fc_code code = rc < 0 ? av_failure(err, "no muxer for", v->path, rc) : open_codec(v, codec, params, err);
    if (code == FC_OK)
        code = alloc_pictures(v, params, err);
    if (code == FC_OK)
        code = open_file(v, err);
    if (code != FC_OK) {
        free_encoder(v);
        return code;
    }
    *out = v;
    return FC_OK;
}

static const char *video_codec_name(const fc_video_file *v)
{
    return v->codec_name;
}

/* Sends `frame` (NULL: end of stream) and writes every packet that is ready. */
static fc_code encode(fc_video_file *v, AVFrame *frame, fc_error *err)
{
    int rc = avcodec_send_frame(v->codec, frame);
    if (rc < 0)
        return av_failure(err, "cannot encode a frame of", v->path, rc);
    for (;;) {
        rc = avcodec_receive_packet(v->codec, v->packet);
        if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF)
            return FC_OK;
        if (rc < 0)
            return av_failure(err, "cannot encode a frame of", v->path, rc);
        av_packet_rescale_ts(v->packet, v->codec->time_base, v->stream->time_base);
        v->packet->stream_index = v->stream->index;
        rc = av_interleaved_write_frame(v->format, v->packet);   /* takes the packet's data */
        if (rc < 0)
            return av_failure(err, "cannot write", v->path, rc);
    }
}

static fc_code video_write_rgba(fc_video_file *v, const uint8_t *rgba, fc_error *err)
{
    int rc = av_frame_make_writable(v->frame);
    if (rc < 0)
        return av_failure(err, "no picture buffer for", v->path, rc);
    const uint8_t *const src[1] = {rgba};
    const int stride[1] = {4 * v->codec->width};
    sws_scale(v->scale, src, stride, 0, v->codec->height, v->frame->data, v->frame->linesize);
    v->frame->pts = v->frames;
    if (v->codec->flags & AV_CODEC_FLAG_QSCALE)
        v->frame->quality = v->codec->global_quality;
    fc_code code = encode(v, v->frame, err);
    if (code == FC_OK)
        v->frames++;
    return code;
}

static fc_code video_close(fc_video_file *v, fc_error *err)
{
    fc_code code = encode(v, NULL, err);
    int rc = av_write_trailer(v->format);
    if (rc < 0 && code == FC_OK)
        code = av_failure(err, "cannot finish", v->path, rc);
    rc = avio_closep(&v->format->pb);
    if (rc < 0 && code == FC_OK)
        code = av_failure(err, "cannot close", v->path, rc);
    free_encoder(v);
    return code;
}

__attribute__((visibility("default"))) extern const fc_video_module fc_video_module_v1;

const fc_video_module fc_video_module_v1 = {
    .abi = FC_VIDEO_MODULE_ABI,
    .open = video_open,
    .codec_name = video_codec_name,
    .write_rgba = video_write_rgba,
    .close = video_close,
};
