/* video_encoder.c — see video_encoder.h. */
#include "video_encoder.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>

#include "fc_error.h"

/* What each container is encoded with, best first. */
typedef struct video_codec {
    const char *encoder;      /* libavcodec encoder name */
    uint32_t default_crf, max_crf;
} video_codec;

static const video_codec mp4_codecs[] = {{"libx264", 23, 51}, {"mpeg4", 23, 51}};
static const video_codec webm_codecs[] = {{"libvpx-vp9", 32, 63}};

struct fc_video_encoder {
    AVFormatContext *format;
    AVCodecContext *codec;
    AVStream *stream;
    struct SwsContext *scale;
    AVFrame *frame;
    AVPacket *packet;
    const char *codec_name;
    uint64_t frames;
    char path[1024];
};

static const char *extension_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot : "";
}

/* The candidates for a path, or NULL when it names no video container. */
static const video_codec *codecs_for(const char *path, size_t *count)
{
    const char *ext = extension_of(path);
    if (strcasecmp(ext, ".mp4") == 0) {
        *count = sizeof mp4_codecs / sizeof mp4_codecs[0];
        return mp4_codecs;
    }
    if (strcasecmp(ext, ".webm") == 0) {
        *count = sizeof webm_codecs / sizeof webm_codecs[0];
        return webm_codecs;
    }
    *count = 0;
    return NULL;
}

bool fc_video_is_video_path(const char *path)
{
    size_t count;
    return codecs_for(path, &count) != NULL;
}

uint32_t fc_video_default_quality(const char *path)
{
    size_t count;
    const video_codec *c = codecs_for(path, &count);
    return c ? c[0].default_crf : 0;
}

uint32_t fc_video_max_quality(const char *path)
{
    size_t count;
    const video_codec *c = codecs_for(path, &count);
    return c ? c[0].max_crf : 0;
}

static fc_code av_failure(fc_error *err, const char *what, const char *path, int averr)
{
    char reason[AV_ERROR_MAX_STRING_SIZE];
    av_strerror(averr, reason, sizeof reason);
    return fc_error_set(err, FC_ERR_IO, "%s %s: %s", what, path, reason);
}

/* The first candidate libavcodec has. */
static const AVCodec *find_encoder(const char *path, fc_error *err)
{
    size_t count;
    const video_codec *c = codecs_for(path, &count);
    for (size_t i = 0; i < count; i++) {
        const AVCodec *codec = avcodec_find_encoder_by_name(c[i].encoder);
        if (codec)
            return codec;
    }
    fc_error_set(err, FC_ERR_IO, "this libavcodec has no encoder for %s (tried %s%s)", path,
                 count ? c[0].encoder : "none", count > 1 ? " and mpeg4" : "");
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

static fc_code open_codec(fc_video_encoder *v, const AVCodec *codec, const fc_video_params *p, fc_error *err)
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

static fc_code alloc_pictures(fc_video_encoder *v, const fc_video_params *p, fc_error *err)
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

static fc_code open_file(fc_video_encoder *v, fc_error *err)
{
    int rc = avio_open(&v->format->pb, v->path, AVIO_FLAG_WRITE);
    if (rc < 0)
        return av_failure(err, "cannot write", v->path, rc);
    rc = avformat_write_header(v->format, NULL);
    return rc < 0 ? av_failure(err, "cannot write the header of", v->path, rc) : FC_OK;
}

static void free_encoder(fc_video_encoder *v)
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

static fc_code check_params(const char *path, const fc_video_params *p, fc_error *err)
{
    if (!fc_video_is_video_path(path))
        return fc_error_set(err, FC_ERR_USAGE, "%s is not a video: use .mp4 or .webm", path);
    if (p->width % 2 || p->height % 2)
        return fc_error_set(err, FC_ERR_USAGE, "video needs an even width and height (yuv420p), not %ux%u",
                            (unsigned)p->width, (unsigned)p->height);
    if (p->fps < 1)
        return fc_error_set(err, FC_ERR_USAGE, "video needs at least 1 frame per second");
    if (strlen(path) >= sizeof ((fc_video_encoder *)0)->path)
        return fc_error_set(err, FC_ERR_USAGE, "the video path is too long");
    return FC_OK;
}

fc_code fc_video_open(const char *path, const fc_video_params *params, fc_video_encoder **out, fc_error *err)
{
    *out = NULL;
    fc_code code = check_params(path, params, err);
    if (code != FC_OK)
        return code;
    const AVCodec *codec = find_encoder(path, err);
    if (!codec)
        return FC_ERR_IO;
    av_log_set_level(AV_LOG_ERROR);   /* libav's log is process-wide; x264 prints statistics at INFO */
    fc_video_encoder *v = calloc(1, sizeof *v);
    if (!v)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the video encoder");
    strcpy(v->path, path);
    int rc = avformat_alloc_output_context2(&v->format, NULL, NULL, path);
    code = rc < 0 ? av_failure(err, "no muxer for", path, rc) : open_codec(v, codec, params, err);
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

const char *fc_video_codec_name(const fc_video_encoder *v)
{
    return v->codec_name;
}

uint64_t fc_video_frame_count(const fc_video_encoder *v)
{
    return v->frames;
}

/* Sends `frame` (NULL: end of stream) and writes every packet that is ready. */
static fc_code encode(fc_video_encoder *v, AVFrame *frame, fc_error *err)
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

fc_code fc_video_write_rgba(fc_video_encoder *v, const uint8_t *rgba, fc_error *err)
{
    int rc = av_frame_make_writable(v->frame);
    if (rc < 0)
        return av_failure(err, "no picture buffer for", v->path, rc);
    const uint8_t *const src[1] = {rgba};
    const int stride[1] = {4 * v->codec->width};
    sws_scale(v->scale, src, stride, 0, v->codec->height, v->frame->data, v->frame->linesize);
    v->frame->pts = (int64_t)v->frames;
    if (v->codec->flags & AV_CODEC_FLAG_QSCALE)
        v->frame->quality = v->codec->global_quality;
    fc_code code = encode(v, v->frame, err);
    if (code == FC_OK)
        v->frames++;
    return code;
}

fc_code fc_video_close(fc_video_encoder *v, fc_error *err)
{
    if (!v)
        return FC_OK;
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
