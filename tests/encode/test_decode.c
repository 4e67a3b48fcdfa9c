/* test_decode.c — fc_decode_image_bytes on image files whose pixels are known
 * independently of the decoder: PNGs written byte by byte (by a Python script
 * with zlib, embedded below), EXRs holding exactly representable floats, a
 * flat-colour JPEG; and the refusals (other formats, truncated files, junk,
 * images beyond the size limit) with their exact codes. */
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "image_decoder.h"
#include "image_encoder.h"
#include "test_util.h"

#define NO_LIMIT 8192u

/* 3x2 RGB, 8-bit: rows (10,20,30 40,50,60 70,80,90) and (100,110,120 130,140,150 160,170,180). */
static const uint8_t png_rgb_3x2[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x03, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x00, 0x00, 0x12, 0x16, 0xf1, 0x4d, 0x00, 0x00, 0x00,
    0x1c, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xe0, 0x12, 0x91, 0xd3, 0x30, 0xb2, 0x71, 0x0b, 0x88, 0x62,
    0x48, 0xc9, 0xab, 0x68, 0xea, 0x99, 0xb6, 0x60, 0xd5, 0x16, 0x00, 0x2e, 0x5e, 0x06, 0xaf, 0x49, 0xb8, 0x0a,
    0x41, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82
};
/* 2x1 grey + alpha, 8-bit: (200, alpha 0), (50, alpha 128). */
static const uint8_t png_grey_alpha_2x1[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x08, 0x04, 0x00, 0x00, 0x00, 0x5e, 0x2b, 0xb7, 0x01, 0x00, 0x00, 0x00,
    0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0x38, 0xc1, 0x60, 0xd4, 0x00, 0x00, 0x04, 0x09, 0x01, 0x7b,
    0xd8, 0x3d, 0xab, 0xa0, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82
};
/* 8193x1 grey, all black: one pixel wider than the protocol allows. */
static const uint8_t png_grey_8193x1[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x20, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00, 0x00, 0xbc, 0xe2, 0x14, 0x82, 0x00, 0x00, 0x00,
    0x1f, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0xed, 0xc1, 0x01, 0x0d, 0x00, 0x00, 0x00, 0xc2, 0xa0, 0xf7, 0x4f,
    0x6d, 0x0e, 0x37, 0xa0, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x7f, 0x03, 0x20, 0x02, 0x00, 0x01,
    0x36, 0x4e, 0xb7, 0x1e, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82
};
/* 1x1 24-bit BMP, red: a format OpenImageIO reads but the protocol does not accept. */
static const uint8_t bmp_red_1x1[] = {
    0x42, 0x4d, 0x3a, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x36, 0x00, 0x00, 0x00, 0x28, 0x00, 0x00, 0x00,
    0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x18, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x00,
    0x00, 0x00, 0x13, 0x0b, 0x00, 0x00, 0x13, 0x0b, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0xff, 0x00
};

static void test_png_rgb_gains_opaque_alpha(void)
{
    static const uint8_t expected[3 * 2 * 4] = {10,  20,  30,  255, 40,  50,  60,  255, 70,  80,  90,  255,
                                                100, 110, 120, 255, 130, 140, 150, 255, 160, 170, 180, 255};
    fc_image img = {0};
    fc_error err;
    CHECK_CODE(fc_decode_image_bytes(png_rgb_3x2, sizeof png_rgb_3x2, NO_LIMIT, &img, &err), FC_OK);
    CHECK(img.width == 3 && img.height == 2 && img.channels == 4 && img.type == FC_PIXEL_U8);
    CHECK(img.pixels && img.capacity >= sizeof expected && memcmp(img.pixels, expected, sizeof expected) == 0);
    free(img.pixels);
}

/* Grey spreads to R, G and B; the alpha stays straight (colour not premultiplied). */
static void test_png_grey_alpha_spreads(void)
{
    static const uint8_t expected[2 * 4] = {200, 200, 200, 0, 50, 50, 50, 128};
    fc_image img = {0};
    fc_error err;
    CHECK_CODE(fc_decode_image_bytes(png_grey_alpha_2x1, sizeof png_grey_alpha_2x1, NO_LIMIT, &img, &err), FC_OK);
    CHECK(img.width == 2 && img.height == 1 && img.channels == 4 && img.type == FC_PIXEL_U8);
    CHECK(img.pixels && memcmp(img.pixels, expected, sizeof expected) == 0);
    free(img.pixels);
}

/* An EXR keeps its floats, beyond [0, 1] and negative too. */
static void test_exr_stays_float(void)
{
    float rgba[2 * 1 * 4] = {0.25f, 3.5f, -1.0f, 0.5f, 100.0f, 0.0f, 0.125f, 1.0f};
    fc_image in = {2, 1, 4, FC_PIXEL_F32, rgba, sizeof rgba};
    fc_buf file;
    fc_buf_init(&file);
    fc_error err;
    CHECK_CODE(fc_encode_image(&in, FC_FORMAT_EXR, 0, &file, &err), FC_OK);
    fc_image img = {0};
    CHECK_CODE(fc_decode_image_bytes(file.data, file.len, NO_LIMIT, &img, &err), FC_OK);
    CHECK(img.width == 2 && img.height == 1 && img.channels == 4 && img.type == FC_PIXEL_F32);
    CHECK(img.pixels && memcmp(img.pixels, rgba, sizeof rgba) == 0);
    free(img.pixels);

    /* One channel ("Z"): grey, opaque. */
    float z[2] = {7.0f, 0.75f};
    fc_image single = {2, 1, 1, FC_PIXEL_F32, z, sizeof z};
    fc_buf_reset(&file);
    CHECK_CODE(fc_encode_image(&single, FC_FORMAT_EXR, 0, &file, &err), FC_OK);
    CHECK_CODE(fc_decode_image_bytes(file.data, file.len, NO_LIMIT, &img, &err), FC_OK);
    const float expected[8] = {7.0f, 7.0f, 7.0f, 1.0f, 0.75f, 0.75f, 0.75f, 1.0f};
    CHECK(img.channels == 4 && img.type == FC_PIXEL_F32 && img.pixels &&
          memcmp(img.pixels, expected, sizeof expected) == 0);
    free(img.pixels);
    fc_buf_free(&file);
}

/* JPEG is lossy, but a flat colour survives within a step or two. */
static void test_jpeg_flat_colour(void)
{
    enum { SIDE = 16 };
    uint8_t px[SIDE * SIDE * 4];
    for (int i = 0; i < SIDE * SIDE; i++)
        memcpy(px + 4 * i, (const uint8_t[4]){200, 60, 20, 255}, 4);
    fc_image in = {SIDE, SIDE, 4, FC_PIXEL_U8, px, sizeof px};
    fc_buf file;
    fc_buf_init(&file);
    fc_error err;
    CHECK_CODE(fc_encode_image(&in, FC_FORMAT_JPEG, 95, &file, &err), FC_OK);
    fc_image img = {0};
    CHECK_CODE(fc_decode_image_bytes(file.data, file.len, NO_LIMIT, &img, &err), FC_OK);
    CHECK(img.width == SIDE && img.height == SIDE && img.channels == 4 && img.type == FC_PIXEL_U8);
    if (img.pixels) {
        const uint8_t *centre = (const uint8_t *)img.pixels + 4 * (SIDE * SIDE / 2 + SIDE / 2);
        CHECK_NEAR(centre[0], 200, 3);
        CHECK_NEAR(centre[1], 60, 3);
        CHECK_NEAR(centre[2], 20, 3);
        CHECK(centre[3] == 255);
    }
    free(img.pixels);
    fc_buf_free(&file);
}

static void test_size_limit(void)
{
    fc_image img = {0};
    fc_error err;
    CHECK_CODE(fc_decode_image_bytes(png_grey_8193x1, sizeof png_grey_8193x1, NO_LIMIT, &img, &err), FC_ERR_LIMIT);
    CHECK_MSG(strstr(err.message, "8193x1") != NULL, "%s", err.message);
    CHECK(img.pixels == NULL && img.width == 0);
    CHECK_CODE(fc_decode_image_bytes(png_rgb_3x2, sizeof png_rgb_3x2, 2, &img, &err), FC_ERR_LIMIT);
    CHECK_CODE(fc_decode_image_bytes(png_rgb_3x2, sizeof png_rgb_3x2, 3, &img, &err), FC_OK);
    free(img.pixels);
}

static void test_refusals(void)
{
    fc_image img = {0};
    fc_error err;
    CHECK_CODE(fc_decode_image_bytes(bmp_red_1x1, sizeof bmp_red_1x1, NO_LIMIT, &img, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "bmp") != NULL, "%s", err.message);
    static const uint8_t junk[64] = "this is a text file, not an image at all, whatever it says";
    CHECK_CODE(fc_decode_image_bytes(junk, sizeof junk, NO_LIMIT, &img, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(fc_decode_image_bytes(junk, 0, NO_LIMIT, &img, &err), FC_ERR_INVALID_VALUE);
    /* Cut inside the IDAT chunk: the header reads, the pixels do not. */
    CHECK_CODE(fc_decode_image_bytes(png_rgb_3x2, 50, NO_LIMIT, &img, &err), FC_ERR_INVALID_VALUE);
    /* Only the signature. */
    CHECK_CODE(fc_decode_image_bytes(png_rgb_3x2, 8, NO_LIMIT, &img, &err), FC_ERR_INVALID_VALUE);
    CHECK(img.pixels == NULL);
    CHECK_CODE(fc_decode_image_bytes(NULL, 4, NO_LIMIT, &img, &err), FC_ERR_USAGE);
}

int main(void)
{
    test_png_rgb_gains_opaque_alpha();
    test_png_grey_alpha_spreads();
    test_exr_stays_float();
    test_jpeg_flat_colour();
    test_size_limit();
    test_refusals();
    return test_result();
}
