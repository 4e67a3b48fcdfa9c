/* test_encode_jpeg.c — JPEG chroma subsampling (settings key 32): the file's
 * own frame header (SOF0, read byte by byte here, not through the encoder)
 * says 4:4:4 or 4:2:0, and the pixels OpenImageIO decodes stay within a
 * bound of the input; on colour that changes every pixel, 4:4:4 keeps it and
 * 4:2:0 blurs it, so the choice really reaches libjpeg. */
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "image_decode.h"
#include "image_encoder.h"
#include "test_util.h"

enum { S = 32 };

typedef struct sampling {
    int components;
    int h[3], v[3];   /* each component's sampling factors */
} sampling;

/* Walks the marker segments from SOI to the first SOF0 (baseline) and reads
 * each component's H and V factors; components = 0 when none is found. */
static sampling read_sof0(const fc_buf *jpeg)
{
    sampling s = {0};
    const uint8_t *p = jpeg->data;
    size_t n = jpeg->len, at = 2;
    while (at + 4 <= n && p[at] == 0xFF) {
        uint8_t marker = p[at + 1];
        size_t length = (size_t)p[at + 2] << 8 | p[at + 3];
        if (marker == 0xC0 && at + 4 + 6 <= n) {
            const uint8_t *sof = p + at + 4;
            s.components = sof[5];
            for (int c = 0; c < s.components && c < 3 && at + 4 + 6 + 3 * (size_t)c + 3 <= n; c++) {
                s.h[c] = sof[6 + 3 * c + 1] >> 4;
                s.v[c] = sof[6 + 3 * c + 1] & 15;
            }
            return s;
        }
        if (marker == 0xDA)
            break;   /* start of scan: no SOF0 before the data */
        at += 2 + length;
    }
    return s;
}

/* A smooth gradient, or (fine) columns alternating red and blue. */
static void fill(uint8_t px[S * S * 4], int fine)
{
    for (int y = 0; y < S; y++) {
        for (int x = 0; x < S; x++) {
            uint8_t *p = px + (y * S + x) * 4;
            if (fine) {
                p[0] = x % 2 ? 0 : 220;
                p[1] = 40;
                p[2] = x % 2 ? 220 : 0;
            } else {
                p[0] = (uint8_t)(40 + x * 4);
                p[1] = (uint8_t)(60 + y * 3);
                p[2] = 150;
            }
            p[3] = 255;
        }
    }
}

/* Encodes px at quality 95 with `mode`, checks the header's factors and
 * returns the largest difference of a decoded sample from the input. */
static int encode_and_compare(const uint8_t *px, fc_jpeg_subsampling mode)
{
    fc_image img = {S, S, 4, FC_PIXEL_U8, (void *)px, 0};
    fc_encode_options options = {95, FC_PNG_DEFAULT_COMPRESSION, mode};
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image_with(&img, FC_FORMAT_JPEG, &options, &out, &err), FC_OK);
    sampling s = read_sof0(&out);
    int luma = mode == FC_JPEG_SUBSAMPLING_YUV420 ? 2 : 1;
    CHECK_MSG(s.components == 3, "SOF0 with %d components", s.components);
    CHECK_MSG(s.h[0] == luma && s.v[0] == luma, "luma sampled %dx%d, expected %dx%d", s.h[0], s.v[0], luma, luma);
    CHECK(s.h[1] == 1 && s.v[1] == 1 && s.h[2] == 1 && s.v[2] == 1);
    int worst = 0;
    fc_decoded_image dec;
    if (fc_decode_image(out.data, out.len, "jpg", 0, &dec, &err) == FC_OK) {
        const uint8_t *got = dec.pixels;
        CHECK(dec.width == S && dec.height == S && dec.channels == 3);
        for (int i = 0; i < S * S; i++)
            for (int c = 0; c < 3; c++) {
                int d = abs((int)got[i * 3 + c] - (int)px[i * 4 + c]);
                worst = d > worst ? d : worst;
            }
        fc_decoded_image_free(&dec);
    } else {
        CHECK_MSG(0, "decode: %s", err.message);
    }
    fc_buf_free(&out);
    return worst;
}

static void test_smooth_colour_within_bound(void)
{
    uint8_t px[S * S * 4];
    fill(px, 0);
    int full = encode_and_compare(px, FC_JPEG_SUBSAMPLING_YUV444);
    int half = encode_and_compare(px, FC_JPEG_SUBSAMPLING_YUV420);
    CHECK_MSG(full <= 6, "4:4:4 differs by %d levels on a gradient", full);
    CHECK_MSG(half <= 8, "4:2:0 differs by %d levels on a gradient", half);
}

static void test_fine_colour_needs_444(void)
{
    uint8_t px[S * S * 4];
    fill(px, 1);
    int full = encode_and_compare(px, FC_JPEG_SUBSAMPLING_YUV444);
    int half = encode_and_compare(px, FC_JPEG_SUBSAMPLING_YUV420);
    CHECK_MSG(full <= 24, "4:4:4 differs by %d levels on 1-pixel colour columns", full);
    CHECK_MSG(half > 60, "4:2:0 kept 1-pixel colour columns (worst %d levels): not subsampled?", half);
}

/* The daemon's old entry point keeps full chroma; an unknown mode is the caller's error. */
static void test_defaults_and_refusals(void)
{
    uint8_t px[S * S * 4];
    fill(px, 0);
    fc_image img = {S, S, 4, FC_PIXEL_U8, px, 0};
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_JPEG, 90, &out, &err), FC_OK);
    sampling s = read_sof0(&out);
    CHECK(s.components == 3 && s.h[0] == 1 && s.v[0] == 1);
    fc_buf_reset(&out);
    fc_encode_options bad = {90, FC_PNG_DEFAULT_COMPRESSION, (fc_jpeg_subsampling)2};
    CHECK_CODE(fc_encode_image_with(&img, FC_FORMAT_JPEG, &bad, &out, &err), FC_ERR_USAGE);
    CHECK(strstr(err.message, "subsampling") != NULL);
    CHECK(out.len == 0);
    CHECK_CODE(fc_encode_image_with(&img, FC_FORMAT_JPEG, NULL, &out, &err), FC_ERR_USAGE);
    fc_buf_free(&out);
}

int main(void)
{
    test_smooth_colour_within_bound();
    test_fine_colour_needs_444();
    test_defaults_and_refusals();
    return test_result();
}
