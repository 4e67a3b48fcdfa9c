/* video_frames.c — see video_frames.h. */
#include "video_frames.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>

typedef struct decoder {
    AVFormatContext *format;
    AVCodecContext *codec;
    struct SwsContext *scale;
    AVFrame *frame;
    AVPacket *packet;
    int stream;
} decoder;

static bool open_decoder(const char *path, decoder *d)
{
    if (avformat_open_input(&d->format, path, NULL, NULL) < 0 || avformat_find_stream_info(d->format, NULL) < 0) {
        fprintf(stderr, "%s: cannot open or probe\n", path);
        return false;
    }
    const AVCodec *codec = NULL;
    d->stream = av_find_best_stream(d->format, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
    if (d->stream < 0 || !codec) {
        fprintf(stderr, "%s: no video stream\n", path);
        return false;
    }
    d->codec = avcodec_alloc_context3(codec);
    d->frame = av_frame_alloc();
    d->packet = av_packet_alloc();
    if (!d->codec || !d->frame || !d->packet ||
        avcodec_parameters_to_context(d->codec, d->format->streams[d->stream]->codecpar) < 0 ||
        avcodec_open2(d->codec, codec, NULL) < 0) {
        fprintf(stderr, "%s: cannot open the %s decoder\n", path, codec->name);
        return false;
    }
    return true;
}

static bool keep_frame(decoder *d, video_frames *out)
{
    if (out->count >= VIDEO_FRAMES_MAX)
        return false;
    AVFrame *f = d->frame;
    out->width = (uint32_t)f->width;
    out->height = (uint32_t)f->height;
    d->scale = sws_getCachedContext(d->scale, f->width, f->height, f->format, f->width, f->height, AV_PIX_FMT_RGB24,
                                    SWS_BICUBIC, NULL, NULL, NULL);
    uint8_t *rgb = malloc((size_t)f->width * f->height * 3);
    if (!d->scale || !rgb) {
        free(rgb);
        return false;
    }
    uint8_t *dst[1] = {rgb};
    int stride[1] = {3 * f->width};
    sws_scale(d->scale, (const uint8_t *const *)f->data, f->linesize, 0, f->height, dst, stride);
    out->rgb[out->count++] = rgb;
    return true;
}

/* Sends a packet (NULL: drain) and keeps every frame that comes out. */
static bool decode(decoder *d, AVPacket *packet, video_frames *out)
{
    if (avcodec_send_packet(d->codec, packet) < 0)
        return false;
    for (;;) {
        int rc = avcodec_receive_frame(d->codec, d->frame);
        if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF)
            return true;
        if (rc < 0 || !keep_frame(d, out))
            return false;
    }
}

bool video_frames_read(const char *path, video_frames *out)
{
    memset(out, 0, sizeof *out);
    av_log_set_level(AV_LOG_ERROR);
    decoder d = {0};
    bool ok = open_decoder(path, &d);
    if (ok)
        snprintf(out->codec, sizeof out->codec, "%s", d.codec->codec->name);
    while (ok && av_read_frame(d.format, d.packet) >= 0) {
        if (d.packet->stream_index == d.stream)
            ok = decode(&d, d.packet, out);
        av_packet_unref(d.packet);
    }
    if (ok)
        ok = decode(&d, NULL, out);
    if (!ok)
        fprintf(stderr, "%s: decoding failed after %u frames\n", path, out->count);
    sws_freeContext(d.scale);
    av_frame_free(&d.frame);
    av_packet_free(&d.packet);
    avcodec_free_context(&d.codec);
    avformat_close_input(&d.format);
    return ok;
}

void video_frames_free(video_frames *v)
{
    for (uint32_t i = 0; i < v->count; i++)
        free(v->rgb[i]);
    memset(v, 0, sizeof *v);
}
