/* test_encode.c — fc_encode_image in every format, decoded back with
 * OpenImageIO (tests/support/image_decode) and compared with values known
 * independently of the encoder: the input bytes themselves or sRGB constants. */
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "image_decode.h"
#include "image_encoder.h"
#include "test_util.h"

enum { W = 4, H = 3 };

/* 8-bit RGBA with every sample distinct, so swapped rows/channels show up. */
static void fill_rgba_u8(uint8_t px[W * H * 4])
{
    for (int i = 0; i < W * H * 4; i++)
        px[i] = (uint8_t)(i * 5 + 3);
}

static fc_image image_of(void *pixels, uint32_t channels, fc_pixel_type type)
{
    fc_image img = {W, H, channels, type, pixels, 0};
    return img;
}

static int starts_with(const fc_buf *b, const char *magic, size_t n)
{
    return b->len >= n && memcmp(b->data, magic, n) == 0;
}

static void test_png_u8_is_lossless(void)
{
    uint8_t px[W * H * 4];
    fill_rgba_u8(px);
    fc_image img = image_of(px, 4, FC_PIXEL_U8);
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_PNG, 0, &out, &err), FC_OK);
    CHECK(starts_with(&out, "\x89PNG\r\n\x1a\n", 8));
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(out.data, out.len, "png", 0, &dec, &err), FC_OK);
    CHECK(dec.width == W && dec.height == H && dec.channels == 4);
    CHECK(dec.pixels && memcmp(dec.pixels, px, sizeof px) == 0);
    fc_decoded_image_free(&dec);
    fc_buf_free(&out);
}

/* Linear floats -> sRGB bytes. Expected values are the sRGB standard's
 * (IEC 61966-2-1) for these inputs; alpha is scaled without the transfer. */
static void test_png_from_float_applies_srgb_and_clamps(void)
{
    static const float linear[] = {0.5f, 0.18f, 0.002f, 0.5f, 2.0f, -1.0f, 0.8f, 1.0f};
    static const uint8_t expected[] = {188, 118, 7, 128, 255, 0, 231, 255};
    float px[W * H * 4];
    for (int i = 0; i < W * H * 4; i++)
        px[i] = linear[i % 8];
    fc_image img = image_of(px, 4, FC_PIXEL_F32);
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_PNG, 0, &out, &err), FC_OK);
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(out.data, out.len, "png", 0, &dec, &err), FC_OK);
    CHECK(dec.channels == 4);
    const uint8_t *got = dec.pixels;
    for (int i = 0; got && i < W * H * 4; i++)
        CHECK_MSG(got[i] == expected[i % 8], "sample %d: got %d expected %d", i, got[i], expected[i % 8]);
    fc_decoded_image_free(&dec);
    fc_buf_free(&out);
}

static void test_png_single_channel(void)
{
    uint8_t px[W * H];
    for (int i = 0; i < W * H; i++)
        px[i] = (uint8_t)(250 - i * 17);
    fc_image img = image_of(px, 1, FC_PIXEL_U8);
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_PNG, 0, &out, &err), FC_OK);
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(out.data, out.len, "png", 0, &dec, &err), FC_OK);
    CHECK(dec.width == W && dec.height == H && dec.channels == 1);
    CHECK(dec.pixels && memcmp(dec.pixels, px, sizeof px) == 0);
    fc_decoded_image_free(&dec);
    fc_buf_free(&out);
}

/* A smooth 16x16 gradient survives JPEG within a few levels; alpha is dropped
 * and a lower quality gives a smaller file. */
static void test_jpeg_quality_and_tolerance(void)
{
    enum { S = 16 };
    uint8_t px[S * S * 4];
    for (int y = 0; y < S; y++) {
        for (int x = 0; x < S; x++) {
            uint8_t *p = px + (y * S + x) * 4;
            p[0] = (uint8_t)(40 + x * 8);
            p[1] = (uint8_t)(60 + y * 6);
            p[2] = 150;
            p[3] = 7;
        }
    }
    fc_image img = {S, S, 4, FC_PIXEL_U8, px, 0};
    fc_buf high, low;
    fc_buf_init(&high);
    fc_buf_init(&low);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_JPEG, 95, &high, &err), FC_OK);
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_JPEG, 5, &low, &err), FC_OK);
    CHECK(starts_with(&high, "\xff\xd8\xff", 3));
    CHECK_MSG(low.len < high.len, "quality 5: %zu bytes, quality 95: %zu bytes", low.len, high.len);
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(high.data, high.len, "jpg", 0, &dec, &err), FC_OK);
    CHECK(dec.width == S && dec.height == S && dec.channels == 3);
    const uint8_t *got = dec.pixels;
    for (int i = 0; got && i < S * S; i++)
        for (int c = 0; c < 3; c++)
            CHECK_NEAR(got[i * 3 + c], px[i * 4 + c], 6);
    fc_decoded_image_free(&dec);
    fc_buf_free(&high);
    fc_buf_free(&low);
}

/* EXR keeps floats bit-exact, including values outside [0,1]. */
static void test_exr_float_rgba_exact(void)
{
    float px[W * H * 4];
    for (int i = 0; i < W * H * 4; i++)
        px[i] = (float)i * 0.37f - 3.0f;
    fc_image img = image_of(px, 4, FC_PIXEL_F32);
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_EXR, 0, &out, &err), FC_OK);
    CHECK(starts_with(&out, "\x76\x2f\x31\x01", 4));
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(out.data, out.len, "exr", 1, &dec, &err), FC_OK);
    CHECK(dec.width == W && dec.height == H && dec.channels == 4);
    CHECK(strcmp(dec.channel_names[0], "R") == 0 && strcmp(dec.channel_names[3], "A") == 0);
    CHECK_MSG(strcmp(dec.compression, "zip") == 0, "compression '%s'", dec.compression);
    CHECK(dec.pixels && memcmp(dec.pixels, px, sizeof px) == 0);
    fc_decoded_image_free(&dec);
    fc_buf_free(&out);
}

static void test_exr_aov_is_single_z_channel(void)
{
    float px[W * H];
    for (int i = 0; i < W * H; i++)
        px[i] = i == 0 ? 0.0f : 100.0f / (float)i;
    fc_image img = image_of(px, 1, FC_PIXEL_F32);
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_EXR, 0, &out, &err), FC_OK);
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(out.data, out.len, "exr", 1, &dec, &err), FC_OK);
    CHECK(dec.channels == 1);
    CHECK_MSG(strcmp(dec.channel_names[0], "Z") == 0, "channel named '%s'", dec.channel_names[0]);
    CHECK(dec.pixels && memcmp(dec.pixels, px, sizeof px) == 0);
    fc_decoded_image_free(&dec);
    fc_buf_free(&out);
}

/* 8-bit colour is sRGB: EXR receives it linearised (188 -> 0.50289), alpha scaled only. */
static void test_exr_from_u8_linearises_colour(void)
{
    uint8_t px[W * H * 4];
    for (int i = 0; i < W * H; i++) {
        px[i * 4 + 0] = 188;
        px[i * 4 + 1] = 255;
        px[i * 4 + 2] = 0;
        px[i * 4 + 3] = 51;
    }
    fc_image img = image_of(px, 4, FC_PIXEL_U8);
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_EXR, 0, &out, &err), FC_OK);
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(out.data, out.len, "exr", 1, &dec, &err), FC_OK);
    const float *got = dec.pixels;
    CHECK(got != NULL);
    if (got) {
        CHECK_NEAR(got[0], 0.50289, 1e-4);
        CHECK_NEAR(got[1], 1.0, 1e-6);
        CHECK_NEAR(got[2], 0.0, 1e-6);
        CHECK_NEAR(got[3], 0.2, 1e-6);
    }
    fc_decoded_image_free(&dec);
    fc_buf_free(&out);
}

/* RAW appends the rows unchanged after whatever the buffer held. */
static void test_raw_is_the_rows_appended(void)
{
    float px[W * H];
    for (int i = 0; i < W * H; i++)
        px[i] = (float)i + 0.25f;
    fc_image img = image_of(px, 1, FC_PIXEL_F32);
    fc_buf out;
    fc_buf_init(&out);
    CHECK(fc_buf_reserve(&out, 3));
    memcpy(out.data, "abc", 3);
    out.len = 3;
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_RAW, 0, &out, &err), FC_OK);
    CHECK(out.len == 3 + sizeof px);
    CHECK(memcmp(out.data, "abc", 3) == 0);
    CHECK(memcmp(out.data + 3, px, sizeof px) == 0);

    uint8_t rgba[W * H * 4];
    fill_rgba_u8(rgba);
    fc_image colour = image_of(rgba, 4, FC_PIXEL_U8);
    fc_buf_reset(&out);
    CHECK_CODE(fc_encode_image(&colour, FC_FORMAT_RAW, 0, &out, &err), FC_OK);
    CHECK(out.len == sizeof rgba && memcmp(out.data, rgba, sizeof rgba) == 0);
    fc_buf_free(&out);
}

/* Refusals leave the output buffer exactly as it was. */
static void test_refusals(void)
{
    uint8_t px[W * H * 4];
    fill_rgba_u8(px);
    fc_image img = image_of(px, 4, FC_PIXEL_U8);
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    CHECK_CODE(fc_encode_image(&img, (fc_image_format)99, 0, &out, &err), FC_ERR_USAGE);
    CHECK(err.code == FC_ERR_USAGE && strstr(err.message, "format") != NULL);
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_JPEG, 0, &out, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_encode_image(&img, FC_FORMAT_JPEG, 101, &out, &err), FC_ERR_USAGE);
    fc_image two = image_of(px, 2, FC_PIXEL_U8);
    CHECK_CODE(fc_encode_image(&two, FC_FORMAT_PNG, 0, &out, &err), FC_ERR_USAGE);
    fc_image empty = image_of(NULL, 4, FC_PIXEL_U8);
    CHECK_CODE(fc_encode_image(&empty, FC_FORMAT_PNG, 0, &out, &err), FC_ERR_USAGE);
    fc_image bad_type = image_of(px, 4, (fc_pixel_type)7);
    CHECK_CODE(fc_encode_image(&bad_type, FC_FORMAT_RAW, 0, &out, &err), FC_ERR_USAGE);
    CHECK(out.len == 0);
    fc_buf_free(&out);
}

/* A stream that is not an image fails to decode: the decoder checks something. */
static void test_decoder_rejects_garbage(void)
{
    static const uint8_t garbage[] = "definitely not a PNG file";
    fc_decoded_image dec;
    fc_error err;
    CHECK_CODE(fc_decode_image(garbage, sizeof garbage, "png", 0, &dec, &err), FC_ERR_PARSE);
}

int main(void)
{
    test_png_u8_is_lossless();
    test_png_from_float_applies_srgb_and_clamps();
    test_png_single_channel();
    test_jpeg_quality_and_tolerance();
    test_exr_float_rgba_exact();
    test_exr_aov_is_single_z_channel();
    test_exr_from_u8_linearises_colour();
    test_raw_is_the_rows_appended();
    test_refusals();
    test_decoder_rejects_garbage();
    return test_result();
}
