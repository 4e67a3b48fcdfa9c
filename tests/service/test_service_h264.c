/* test_service_h264.c — H.264 video streams (PROTOCOL.md 10.7) from the real
 * fluidcastd, decoded with libavcodec: three viewers of one session watch it
 * as H.264, JPEG and RAW with one camera; every H.264 frame decodes to the
 * RAW frame's pixels (and the JPEG's) within a PSNR bound. The first image is
 * an IDR frame with its SPS and PPS (NAL types 7, 8, 5), the next ones are
 * not; frames skipped by latest-wins leave the stream decodable; a key frame
 * comes on request, at a resize and after a failed image; a viewer at rest
 * gets a lossless PNG refresh; a RENDER's H.264 image is an IDR of its own;
 * after a stream image the viewer never got (a lost GPU context, by the
 * daemon's test hook) the next one is an IDR and decodes; a CAMERA whose
 * stream encoder would not fit --max-session-memory is refused with LIMIT;
 * viewers that join and vanish mid-stream leave the daemon serving the others
 * (their encoders freed: the sanitizer build checks the daemon leaks nothing). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libavcodec/avcodec.h>
#include <libswscale/swscale.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_util.h"

enum { W = 128, H = 96, W2 = 96, H2 = 64, PACED_FRAMES = 4, BURST_FRAMES = 6, VANISHING_VIEWERS = 12 };
#define SESSION "h264"
#define EYE_Z 1.2f
#define MIN_PSNR_DB 30.0

static const char *const daemon_args[] = {"--max-image", "256x256", "--refresh-ms", "500", NULL};

/* ---- Decoding with libavcodec ---- */

typedef struct decoder {
    AVCodecContext *ctx;
    AVPacket *packet;
    AVFrame *frame;
} decoder;

typedef struct picture {
    uint8_t *rgba;
    int width, height;
} picture;

static bool decoder_open(decoder *d, enum AVCodecID id)
{
    memset(d, 0, sizeof *d);
    const AVCodec *codec = avcodec_find_decoder(id);
    d->ctx = codec ? avcodec_alloc_context3(codec) : NULL;
    d->packet = av_packet_alloc();
    d->frame = av_frame_alloc();
    if (!d->ctx || !d->packet || !d->frame)
        return false;
    d->ctx->thread_count = 1;
    d->ctx->flags |= AV_CODEC_FLAG_LOW_DELAY;   /* each access unit out as it comes in */
    return avcodec_open2(d->ctx, codec, NULL) == 0;
}

static void decoder_close(decoder *d)
{
    avcodec_free_context(&d->ctx);
    av_packet_free(&d->packet);
    av_frame_free(&d->frame);
}

/* Decodes one packet into RGBA (libswscale, the stream's matrix); false when it yields no picture. */
static bool decode(decoder *d, const uint8_t *data, size_t size, picture *out)
{
    memset(out, 0, sizeof *out);
    if (av_new_packet(d->packet, (int)size) < 0)
        return false;
    memcpy(d->packet->data, data, size);
    int rc = avcodec_send_packet(d->ctx, d->packet);
    av_packet_unref(d->packet);
    if (rc < 0 || avcodec_receive_frame(d->ctx, d->frame) < 0)
        return false;
    int w = d->frame->width, h = d->frame->height;
    struct SwsContext *sws = sws_getContext(w, h, d->frame->format, w, h, AV_PIX_FMT_RGBA, SWS_BILINEAR, NULL,
                                            NULL, NULL);
    out->rgba = malloc((size_t)w * h * 4);
    bool ok = sws && out->rgba;
    if (ok) {
        uint8_t *dst[1] = {out->rgba};
        int stride[1] = {4 * w};
        sws_scale(sws, (const uint8_t *const *)d->frame->data, d->frame->linesize, 0, h, dst, stride);
        out->width = w;
        out->height = h;
    }
    sws_freeContext(sws);
    av_frame_unref(d->frame);
    return ok;
}

/* PSNR of the RGB channels of two RGBA images of one size. */
static double psnr(const uint8_t *a, const uint8_t *b, int width, int height)
{
    double sum = 0.0;
    size_t n = (size_t)width * height;
    for (size_t i = 0; i < n; i++)
        for (int ch = 0; ch < 3; ch++) {
            double e = (double)a[4 * i + ch] - (double)b[4 * i + ch];
            sum += e * e;
        }
    double mse = sum / (double)(3 * n);
    return mse <= 0.0 ? 99.0 : 10.0 * log10(255.0 * 255.0 / mse);
}

/* ---- Annex B ---- */

/* The NAL unit types of an Annex B access unit, as a bit mask (bit t: type t present). */
static uint32_t nal_types(const uint8_t *p, size_t n)
{
    uint32_t types = 0;
    for (size_t i = 0; i + 3 < n; i++)
        if (p[i] == 0 && p[i + 1] == 0 && p[i + 2] == 1) {
            types |= 1u << (p[i + 3] & 0x1f);
            i += 2;
        }
    return types;
}

static bool is_idr_unit(const uint8_t *p, size_t n)
{
    uint32_t t = nal_types(p, n);
    return (t & (1u << 7)) && (t & (1u << 8)) && (t & (1u << 5));
}

/* ---- The session ---- */

typedef struct scene {
    fc_client *producer;
    fc_client *h264, *jpeg, *raw;
    decoder h264_decoder, jpeg_decoder;
    fc_camera camera;
    fc_settings settings;
    size_t h264_bytes, jpeg_bytes;
    int sized_frames;
} scene;

/* Subscribes a viewer with the scene's camera and settings, applied before the first frame. */
static fc_client *viewer(const fc_test_daemon *d, const scene *s, fc_image_format format, const char *name)
{
    fc_client *c = svc_client(d, name);
    fc_render_request request = {.format = format, .quality = 0, .aov = FC_AOV_COLOR};
    fc_error err;
    fc_session_status *list = NULL;
    uint32_t count = 0;
    bool ok = c && fc_client_subscribe(c, SESSION, &request, W, H, NULL, &err) == FC_OK &&
              fc_client_set_camera(c, &s->camera, &err) == FC_OK &&
              fc_client_set_settings(c, &s->settings, &err) == FC_OK &&
              /* a round trip: the daemon has taken the camera before any frame arrives */
              fc_client_list_sessions(c, &list, &count, &err) == FC_OK;
    CHECK_MSG(ok, "%s viewer: %s", name, c ? err.message : "no connection");
    fc_session_list_free(list);
    return c;
}

/* The next stream image that is not a lossless refresh. */
static bool next_image(fc_client *c, fc_stream_image *out, const char *who)
{
    fc_error err;
    for (;;) {
        fc_code code = fc_client_next_image(c, out, &err);
        if (code != FC_OK) {
            CHECK_MSG(0, "%s: next image: %s", who, err.message);
            return false;
        }
        if (!out->refresh)
            return true;
        fc_stream_image_free(out);
    }
}

static bool publish(scene *s, uint64_t f)
{
    fc_frame frame = {0};
    fc_error err;
    bool ok = svc_grid_frame(0.03f * (float)f, &frame, &err) == FC_OK &&
              fc_client_send_frame(s->producer, &frame, &err) == FC_OK;
    CHECK_MSG(ok, "frame %llu: %s", (unsigned long long)f, err.message);
    fc_frame_free(&frame);
    return ok;
}

/* Decodes an H.264 image and compares it with the RAW image of the same frame. */
static void check_against_raw(scene *s, const fc_stream_image *h, const fc_stream_image *raw, picture *decoded)
{
    bool ok = decode(&s->h264_decoder, h->image.data, h->image.size, decoded);
    CHECK_MSG(ok, "frame %llu: the access unit does not decode", (unsigned long long)h->frame_number);
    if (!ok)
        return;
    CHECK(decoded->width == (int)raw->image.width && decoded->height == (int)raw->image.height);
    CHECK(raw->image.size == (size_t)raw->image.width * raw->image.height * 4);
    if (decoded->width != (int)raw->image.width || raw->image.size != (size_t)decoded->width * decoded->height * 4)
        return;
    double db = psnr(decoded->rgba, raw->image.data, decoded->width, decoded->height);
    printf("frame %llu: H.264 %zu bytes%s, PSNR %.1f dB against RAW\n", (unsigned long long)h->frame_number,
           h->image.size, h->keyframe ? " (IDR)" : "", db);
    CHECK_MSG(db >= MIN_PSNR_DB, "frame %llu: PSNR %.1f dB", (unsigned long long)h->frame_number, db);
}

/* Frames published one at a time, each read by all three viewers. */
static void paced_frames(scene *s)
{
    for (uint64_t f = 1; f <= PACED_FRAMES; f++) {
        if (!publish(s, f))
            return;
        fc_stream_image h, j, r;
        if (!next_image(s->h264, &h, "h264") || !next_image(s->jpeg, &j, "jpeg") || !next_image(s->raw, &r, "raw"))
            return;
        CHECK(h.frame_number == f && j.frame_number == f && r.frame_number == f);
        CHECK(h.image.format == FC_FORMAT_H264 && h.image.width == W && h.image.height == H);
        CHECK_MSG((f == 1) == (h.keyframe != 0), "frame %llu keyframe flag %d", (unsigned long long)f, h.keyframe);
        CHECK_MSG((f == 1) == is_idr_unit(h.image.data, h.image.size), "frame %llu NAL types 0x%x",
                  (unsigned long long)f, nal_types(h.image.data, h.image.size));
        if (f > 1)
            CHECK_MSG(nal_types(h.image.data, h.image.size) & (1u << 1), "frame %llu: no non-IDR slice",
                      (unsigned long long)f);
        picture hp, jp;
        check_against_raw(s, &h, &r, &hp);
        if (hp.rgba && decode(&s->jpeg_decoder, j.image.data, j.image.size, &jp)) {
            double db = psnr(hp.rgba, jp.rgba, W, H);
            printf("frame %llu: JPEG %zu bytes, H.264 against JPEG %.1f dB\n", (unsigned long long)f, j.image.size,
                   db);
            CHECK_MSG(db >= MIN_PSNR_DB, "H.264 against JPEG: %.1f dB", db);
            free(jp.rgba);
        } else {
            CHECK_MSG(0, "frame %llu: no pictures to compare with JPEG", (unsigned long long)f);
        }
        s->h264_bytes += h.image.size;
        s->jpeg_bytes += j.image.size;
        s->sized_frames++;
        free(hp.rgba);
        fc_stream_image_free(&h);
        fc_stream_image_free(&j);
        fc_stream_image_free(&r);
    }
}

/* Reads a viewer's images up to frame `last`; the H.264 ones are all decoded, in order. */
static bool drain_to(scene *s, fc_client *c, uint64_t last, fc_stream_image *final, uint32_t *missed,
                     uint32_t *keyframes)
{
    for (;;) {
        if (!next_image(c, final, "drain"))
            return false;
        *missed += final->missed;
        *keyframes += final->keyframe != 0;
        if (final->frame_number == last)
            return true;
        if (final->image.format == FC_FORMAT_H264) {
            picture p;
            CHECK_MSG(decode(&s->h264_decoder, final->image.data, final->image.size, &p), "frame %llu",
                      (unsigned long long)final->frame_number);
            free(p.rgba);
        }
        fc_stream_image_free(final);
    }
}

/* Frames published faster than the viewers take them: latest wins, frames are
 * skipped (never encoded), and the P-frames that follow still decode right. */
static void burst_frames(scene *s)
{
    uint64_t last = PACED_FRAMES + BURST_FRAMES;
    for (uint64_t f = PACED_FRAMES + 1; f <= last; f++)
        if (!publish(s, f))
            return;
    fc_stream_image h, r, j;
    uint32_t missed = 0, keyframes = 0, raw_missed = 0, raw_keys = 0;
    if (!drain_to(s, s->h264, last, &h, &missed, &keyframes) || !drain_to(s, s->raw, last, &r, &raw_missed, &raw_keys))
        return;
    printf("burst: the H.264 viewer missed %u of %d frames, %u key frames\n", missed, BURST_FRAMES, keyframes);
    CHECK_MSG(missed > 0, "no frame skipped in a burst of %d", BURST_FRAMES);
    CHECK_MSG(keyframes == 0, "%u key frames after skipped frames", keyframes);
    picture p;
    check_against_raw(s, &h, &r, &p);
    free(p.rgba);
    uint32_t jm = 0, jk = 0;
    if (drain_to(s, s->jpeg, last, &j, &jm, &jk))
        fc_stream_image_free(&j);
    fc_stream_image_free(&h);
    fc_stream_image_free(&r);
}

/* The H.264 viewer's next image: the current frame again (a VIEW image), decoded. */
static bool view_image(scene *s, const char *what, fc_stream_image *h, picture *p)
{
    if (!next_image(s->h264, h, what))
        return false;
    CHECK_MSG(h->view_change && h->keyframe && is_idr_unit(h->image.data, h->image.size),
              "%s: view %d keyframe %d NAL types 0x%x", what, h->view_change, h->keyframe,
              nal_types(h->image.data, h->image.size));
    bool ok = decode(&s->h264_decoder, h->image.data, h->image.size, p);
    CHECK_MSG(ok, "%s: does not decode", what);
    return ok;
}

static void keyframe_on_request(scene *s)
{
    fc_error err;
    CHECK_CODE(fc_client_request_keyframe(s->h264, &err), FC_OK);
    fc_stream_image h;
    picture p;
    if (view_image(s, "key frame request", &h, &p)) {
        CHECK(p.width == W && p.height == H);
        printf("requested key frame: %zu bytes\n", h.image.size);
    }
    free(p.rgba);
    fc_stream_image_free(&h);
}

static void resize(scene *s, uint32_t width, uint32_t height, const char *what)
{
    fc_camera camera = s->camera;
    camera.width = width;
    camera.height = height;
    fc_error err;
    CHECK_CODE(fc_client_set_camera(s->h264, &camera, &err), FC_OK);
    fc_stream_image h;
    picture p;
    if (view_image(s, what, &h, &p))
        CHECK_MSG(p.width == (int)width && p.height == (int)height && h.image.width == width &&
                      h.image.height == height,
                  "%s: decoded %dx%d", what, p.width, p.height);
    free(p.rgba);
    fc_stream_image_free(&h);
}

/* An odd size cannot be 4:2:0: ENCODE, the subscription stays, and the image after it is an IDR. */
static void failed_image(scene *s)
{
    fc_camera camera = s->camera;
    camera.width = W2 + 1;
    camera.height = H2;
    fc_error err;
    fc_stream_image h;
    CHECK_CODE(fc_client_set_camera(s->h264, &camera, &err), FC_OK);
    CHECK_CODE(fc_client_next_image(s->h264, &h, &err), FC_ERR_ENCODE);
    printf("odd size: %s\n", err.message);
    resize(s, W2, H2, "after a failed image");
}

static void refresh_at_rest(scene *s)
{
    svc_sleep_ms(700);
    fc_stream_image h;
    fc_error err;
    CHECK_CODE(fc_client_next_image(s->h264, &h, &err), FC_OK);
    CHECK_MSG(h.refresh && h.image.format == FC_FORMAT_PNG && !h.keyframe, "refresh %d format %d", h.refresh,
              (int)h.image.format);
    fc_stream_image_free(&h);
}

static void render_one(scene *s)
{
    fc_render_request request = {.format = FC_FORMAT_H264, .quality = 0, .aov = FC_AOV_COLOR};
    fc_image_result image = {0};
    fc_error err;
    CHECK_CODE(fc_client_set_camera(s->producer, &s->camera, &err), FC_OK);
    CHECK_CODE(fc_client_render(s->producer, &request, &image, &err), FC_OK);
    CHECK(image.format == FC_FORMAT_H264 && is_idr_unit(image.data, image.size));
    decoder d;
    picture p = {0};
    CHECK(decoder_open(&d, AV_CODEC_ID_H264) && decode(&d, image.data, image.size, &p));
    CHECK(p.width == W && p.height == H);
    free(p.rgba);
    decoder_close(&d);
    fc_image_result_free(&image);
}

/* Viewers that join (their first image an IDR) and vanish without a word,
 * some with an image in flight; the daemon keeps serving the RAW viewer. */
static void vanishing_viewers(const fc_test_daemon *d, scene *s)
{
    uint64_t f = PACED_FRAMES + BURST_FRAMES;
    fc_render_request request = {.format = FC_FORMAT_H264, .quality = 0, .aov = FC_AOV_COLOR};
    fc_error err;
    for (int i = 0; i < VANISHING_VIEWERS; i++) {
        fc_client *v = svc_client(d, "vanishing");
        if (!v || fc_client_subscribe(v, SESSION, &request, W, H, NULL, &err) != FC_OK) {
            CHECK_MSG(0, "vanishing viewer %d: %s", i, v ? err.message : "no connection");
            fc_client_close(v);
            return;
        }
        if (i % 2 == 0) {
            fc_stream_image h;
            if (next_image(v, &h, "vanishing"))
                CHECK(h.keyframe && is_idr_unit(h.image.data, h.image.size));
            fc_stream_image_free(&h);
        }
        fc_client_close(v);
        if (i % 3 == 0 && publish(s, ++f)) {
            fc_stream_image r;
            uint32_t m = 0, k = 0;
            if (drain_to(s, s->raw, f, &r, &m, &k))
                fc_stream_image_free(&r);
        }
    }
}

/* A daemon whose 3rd render loses the GPU context: the viewer's image of
 * frame 3 is an ERROR (RENDER), and its image of frame 4 an IDR that decodes. */
static void forced_miss(void)
{
    static const char *const environment[] = {"FLUIDCASTD_TEST_LOSE_CONTEXT=3", NULL};
    /* Room for the encoder at 128x96 (24 bytes per pixel + 4 MiB, conversation_memory.h), not at 256x256. */
    static const char *const args[] = {"--max-image", "256x256", "--refresh-ms", "0", "--max-session-memory",
                                       "5000000", NULL};
    fc_test_daemon_setup setup = {.extra_args = args, .environment = environment};
    fc_test_daemon d;
    fc_error err;
    if (fc_test_daemon_start_with(&d, &setup, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        CHECK_MSG(0, "cannot start the daemon: %s", err.message);
        return;
    }
    scene s = {0};
    svc_axis_camera(EYE_Z, W, H, &s.camera);
    svc_settings(&s.settings);
    s.producer = svc_client(&d, "producer");
    CHECK(s.producer && fc_client_publish(s.producer, SESSION, NULL, &err) == FC_OK);
    s.h264 = viewer(&d, &s, FC_FORMAT_H264, "h264");
    CHECK(decoder_open(&s.h264_decoder, AV_CODEC_ID_H264));
    for (uint64_t f = 1; s.producer && s.h264 && f <= 5 && publish(&s, f); f++) {
        fc_stream_image h;
        fc_code code = fc_client_next_image(s.h264, &h, &err);
        if (f == 3) {
            CHECK_MSG(code == FC_ERR_RENDER, "frame 3: code %d (%s), expected RENDER", (int)code, err.message);
            continue;
        }
        CHECK_MSG(code == FC_OK && h.frame_number == f, "frame %llu: code %d", (unsigned long long)f, (int)code);
        if (code != FC_OK)
            break;
        bool idr = is_idr_unit(h.image.data, h.image.size);
        CHECK_MSG((f == 1 || f == 4) == (h.keyframe && idr), "frame %llu: keyframe %d, NAL types 0x%x",
                  (unsigned long long)f, h.keyframe, nal_types(h.image.data, h.image.size));
        picture p;
        CHECK_MSG(decode(&s.h264_decoder, h.image.data, h.image.size, &p) && p.width == W && p.height == H,
                  "frame %llu does not decode", (unsigned long long)f);
        if (f == 4)
            printf("after the failed image: frame 4 an IDR of %zu bytes\n", h.image.size);
        free(p.rgba);
        fc_stream_image_free(&h);
    }
    fc_camera big = s.camera;
    big.width = big.height = 256;
    fc_stream_image h;
    CHECK_CODE(fc_client_set_camera(s.h264, &big, &err), FC_OK);
    CHECK_CODE(fc_client_next_image(s.h264, &h, &err), FC_ERR_LIMIT);
    printf("a larger stream: %s\n", err.message);
    /* The stream goes on at its size. */
    if (publish(&s, 6) && next_image(s.h264, &h, "after the refused camera")) {
        CHECK(h.frame_number == 6 && h.image.width == W && h.image.height == H && !h.keyframe);
        fc_stream_image_free(&h);
    }
    decoder_close(&s.h264_decoder);
    fc_client_close(s.h264);
    fc_client_close(s.producer);
    CHECK(svc_stop_daemon(&d));
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, daemon_args);
    scene s = {0};
    fc_error err;
    svc_axis_camera(EYE_Z, W, H, &s.camera);
    svc_settings(&s.settings);
    s.producer = svc_client(&daemon, "producer");
    CHECK(s.producer && fc_client_publish(s.producer, SESSION, NULL, &err) == FC_OK);
    CHECK(fc_client_set_settings(s.producer, &s.settings, &err) == FC_OK);
    s.h264 = viewer(&daemon, &s, FC_FORMAT_H264, "h264");
    s.jpeg = viewer(&daemon, &s, FC_FORMAT_JPEG, "jpeg");
    s.raw = viewer(&daemon, &s, FC_FORMAT_RAW, "raw");
    CHECK(decoder_open(&s.h264_decoder, AV_CODEC_ID_H264) && decoder_open(&s.jpeg_decoder, AV_CODEC_ID_MJPEG));
    if (s.producer && s.h264 && s.jpeg && s.raw) {
        paced_frames(&s);
        if (s.sized_frames)
            printf("%dx%d: JPEG %zu bytes per frame, H.264 %zu (first frame an IDR)\n", W, H,
                   s.jpeg_bytes / (size_t)s.sized_frames, s.h264_bytes / (size_t)s.sized_frames);
        burst_frames(&s);
        keyframe_on_request(&s);
        resize(&s, W2, H2, "resize");
        failed_image(&s);
        refresh_at_rest(&s);
        render_one(&s);
        vanishing_viewers(&daemon, &s);
        CHECK_CODE(fc_client_leave_session(s.h264, &err), FC_OK);
    }
    decoder_close(&s.h264_decoder);
    decoder_close(&s.jpeg_decoder);
    fc_client_close(s.h264);
    fc_client_close(s.jpeg);
    fc_client_close(s.raw);
    fc_client_close(s.producer);
    CHECK(svc_stop_daemon(&daemon));
    forced_miss();
    return test_result();
}
