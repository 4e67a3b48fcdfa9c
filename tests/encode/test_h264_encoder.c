/* test_h264_encoder.c — server/encode/h264_encoder.c alone: the quality to CRF
 * mapping, odd sizes and wrong images refused with ENCODE, the first access
 * unit an IDR with SPS and PPS, the next ones not unless forced, and every
 * unit decoding (libavcodec) to its picture: a gradient that moves one pixel
 * per frame, within 35 dB. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <libavcodec/avcodec.h>

#include "fc_error.h"
#include "h264_encoder.h"
#include "test_util.h"

enum { W = 64, H = 48 };

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

/* A diagonal gradient shifted by `shift` pixels, RGBA8. */
static void gradient(fc_image *img, int shift)
{
    uint8_t *p = img->pixels;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++, p += 4) {
            p[0] = (uint8_t)((x + shift) * 3);
            p[1] = (uint8_t)(y * 4);
            p[2] = (uint8_t)(128 + (x + y + shift) % 64);
            p[3] = 255;
        }
}

/* PSNR of the decoded luma against the picture's BT.601 limited-range luma. */
static double luma_psnr(const AVFrame *f, const fc_image *img)
{
    const uint8_t *p = img->pixels;
    double sum = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *q = p + ((size_t)y * W + x) * 4;
            double expected = 16.0 + (65.481 * q[0] + 128.553 * q[1] + 24.966 * q[2]) / 255.0;
            double e = f->data[0][y * f->linesize[0] + x] - expected;
            sum += e * e;
        }
    double mse = sum / (W * H);
    return mse <= 0 ? 99.0 : 10.0 * log10(255.0 * 255.0 / mse);
}

static void test_quality_and_refusals(void)
{
    CHECK(fc_h264_crf_for_quality(90) == 23 && fc_h264_crf_for_quality(100) == 20 &&
          fc_h264_crf_for_quality(1) == 51 && fc_h264_crf_for_quality(0) == 51);
    CHECK(fc_h264_encoder_memory(1280, 720) == 24ull * 1280 * 720 + (4u << 20));
    fc_h264_encoder *enc = NULL;
    fc_error err;
    CHECK_CODE(fc_h264_encoder_create(W + 1, H, 90, &enc, &err), FC_ERR_ENCODE);
    CHECK_CODE(fc_h264_encoder_create(W, 0, 90, &enc, &err), FC_ERR_ENCODE);
    CHECK(enc == NULL);
    CHECK_CODE(fc_h264_encoder_create(W, H, 90, &enc, &err), FC_OK);
    fc_image wrong = {W / 2, H / 2, 4, FC_PIXEL_U8, calloc((size_t)W * H, 4), (size_t)W * H * 4};
    fc_buf out;
    fc_buf_init(&out);
    bool key;
    CHECK_CODE(fc_h264_encoder_encode(enc, &wrong, false, &out, &key, &err), FC_ERR_ENCODE);
    wrong.width = W;
    wrong.height = H;
    wrong.channels = 1;
    CHECK_CODE(fc_h264_encoder_encode(enc, &wrong, false, &out, &key, &err), FC_ERR_ENCODE);
    CHECK(out.len == 0);
    free(wrong.pixels);
    fc_buf_free(&out);
    fc_h264_encoder_free(enc);
}

static void test_stream(void)
{
    fc_h264_encoder *enc = NULL;
    fc_error err;
    CHECK_CODE(fc_h264_encoder_create(W, H, 90, &enc, &err), FC_OK);
    const AVCodec *codec = avcodec_find_decoder(AV_CODEC_ID_H264);
    AVCodecContext *dec = codec ? avcodec_alloc_context3(codec) : NULL;
    AVPacket *pkt = av_packet_alloc();
    AVFrame *frame = av_frame_alloc();
    CHECK(enc && dec && pkt && frame);
    if (!enc || !dec || !pkt || !frame)
        return;
    dec->flags |= AV_CODEC_FLAG_LOW_DELAY;
    CHECK(avcodec_open2(dec, codec, NULL) == 0);
    fc_image img = {W, H, 4, FC_PIXEL_U8, malloc((size_t)W * H * 4), (size_t)W * H * 4};
    fc_buf out;
    fc_buf_init(&out);
    for (int f = 0; f < 6; f++) {
        gradient(&img, f);
        bool forced = f == 4, key;
        fc_buf_reset(&out);
        CHECK_CODE(fc_h264_encoder_encode(enc, &img, forced, &out, &key, &err), FC_OK);
        uint32_t types = nal_types(out.data, out.len);
        bool idr = (types & (1u << 7)) && (types & (1u << 8)) && (types & (1u << 5));
        CHECK_MSG(key == (f == 0 || forced) && idr == key, "frame %d: key %d, NAL types 0x%x", f, key, types);
        CHECK(av_new_packet(pkt, (int)out.len) == 0);
        memcpy(pkt->data, out.data, out.len);
        CHECK(avcodec_send_packet(dec, pkt) == 0);
        av_packet_unref(pkt);
        CHECK_MSG(avcodec_receive_frame(dec, frame) == 0, "frame %d: no picture out", f);
        if (frame->width == W && frame->height == H) {
            double db = luma_psnr(frame, &img);
            CHECK_MSG(db >= 35.0, "frame %d: luma PSNR %.1f dB", f, db);
        }
        av_frame_unref(frame);
    }
    free(img.pixels);
    fc_buf_free(&out);
    av_frame_free(&frame);
    av_packet_free(&pkt);
    avcodec_free_context(&dec);
    fc_h264_encoder_free(enc);
}

int main(void)
{
    test_quality_and_refusals();
    test_stream();
    return test_result();
}
