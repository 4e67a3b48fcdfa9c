/* test_encode_png.c — fluidcast's PNG writer (png_encoder.h), its image data
 * deflated in strips on several threads. Every file is read back twice: by
 * OpenImageIO (libpng) and by this test's own reader (chunk CRCs with zlib's
 * crc32, the IDATs inflated by zlib, which checks the adler32, the rows
 * unfiltered here); both must give the input pixels exactly. Sizes split
 * unevenly into strips, images smaller than one strip, rows longer than a
 * strip, 1/3/4 channels, levels 0..9, thread counts 1..8 and automatic: the
 * bytes must not depend on the thread count, and the strips must compress as
 * well as one zlib stream of the same filtered rows. */
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "fc_error.h"
#include "image_decode.h"
#include "image_encoder.h"
#include "png_encoder.h"
#include "test_util.h"

/* Deterministic content: a smooth gradient with noise in its low bits (like a
 * render: compressible, but not trivially), or pure noise. */
static uint8_t *make_pixels(uint32_t w, uint32_t h, uint32_t ch, uint32_t seed, int noise_only)
{
    size_t n = (size_t)w * h * ch;
    uint8_t *px = malloc(n ? n : 1);
    uint32_t state = seed * 2654435761u + 1;
    for (size_t i = 0; px && i < n; i++) {
        state = state * 1664525u + 1013904223u;
        size_t pixel = i / ch, x = pixel % w, y = pixel / w;
        uint8_t smooth = (uint8_t)((x * 3 + y * 2 + (i % ch) * 50) & 0xff);
        px[i] = noise_only ? (uint8_t)(state >> 24) : (uint8_t)(smooth + ((state >> 29) & 3));
    }
    return px;
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* What this test's reader found in a file. */
typedef struct png_read {
    uint32_t width, height, channels;
    uint8_t *pixels;   /* unfiltered rows */
    uint8_t *filtered; /* the inflated stream: filter byte + row, per row */
    size_t filtered_len;
    size_t zlib_len;   /* the IDATs' data: the zlib stream */
    char chunks[64];   /* second letters of the chunk types in order, e.g. "HFDDE" */
} png_read;

/* Walks the chunks (CRC checked), inflates the IDATs and undoes the filters
 * (NONE or SUB, all this writer may use: `want_filter`). 0 on any fault. */
static int read_png(const fc_buf *file, int want_filter, png_read *r)
{
    memset(r, 0, sizeof *r);
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    CHECK(file->len >= 8 && memcmp(file->data, signature, 8) == 0);
    uint8_t *idat = malloc(file->len);
    size_t idat_len = 0, pos = 8, nchunks = 0;
    int ok = idat != NULL, ended = 0;
    while (ok && !ended && pos + 12 <= file->len) {
        uint32_t len = get_u32(file->data + pos);
        const uint8_t *type = file->data + pos + 4, *data = type + 4;
        if (len > file->len - pos - 12) {
            CHECK_MSG(0, "chunk at %zu: length %u past the end", pos, len);
            ok = 0;
            break;
        }
        uint32_t crc = (uint32_t)crc32(crc32(0, NULL, 0), type, 4 + len);
        CHECK_MSG(crc == get_u32(data + len), "chunk %.4s at %zu: CRC %08x, stored %08x", (const char *)type, pos,
                  crc, get_u32(data + len));
        ok = ok && crc == get_u32(data + len);
        if (nchunks + 1 < sizeof r->chunks)
            r->chunks[nchunks++] = (char)type[1];
        if (memcmp(type, "IHDR", 4) == 0 && len == 13) {
            r->width = get_u32(data);
            r->height = get_u32(data + 4);
            CHECK(data[8] == 8 && data[10] == 0 && data[11] == 0 && data[12] == 0);
            r->channels = data[9] == 0 ? 1 : data[9] == 2 ? 3 : data[9] == 6 ? 4 : 0;
        } else if (memcmp(type, "IDAT", 4) == 0) {
            memcpy(idat + idat_len, data, len);
            idat_len += len;
        } else if (memcmp(type, "IEND", 4) == 0) {
            ended = 1;
            CHECK_MSG(pos + 12 + len == file->len, "bytes after IEND");
        }
        pos += 12 + (size_t)len;
    }
    CHECK(ended);
    ok = ok && ended && r->channels != 0;
    r->zlib_len = idat_len;
    size_t row = (size_t)r->width * r->channels;
    r->filtered_len = ok ? (row + 1) * r->height : 0;
    r->filtered = ok ? malloc(r->filtered_len + 1) : NULL;
    uLongf got = r->filtered_len + 1;
    /* uncompress checks the zlib header and the adler32. */
    int rc = r->filtered ? uncompress(r->filtered, &got, idat, idat_len) : Z_MEM_ERROR;
    CHECK_MSG(!ok || (rc == Z_OK && got == r->filtered_len), "inflate: %d, %lu of %zu bytes", rc,
              (unsigned long)got, r->filtered_len);
    ok = ok && rc == Z_OK && got == r->filtered_len;
    CHECK_MSG(!ok || (idat[0] == 0x78 && (idat[0] * 256 + idat[1]) % 31 == 0), "zlib header %02x %02x", idat[0],
              idat[1]);
    free(idat);
    r->pixels = ok ? malloc(row * r->height) : NULL;
    for (uint32_t y = 0; r->pixels && y < r->height; y++) {
        const uint8_t *in = r->filtered + y * (row + 1);
        uint8_t *out = r->pixels + y * row;
        CHECK_MSG(in[0] == want_filter, "row %u: filter %d, expected %d", y, in[0], want_filter);
        for (size_t i = 0; i < row; i++)
            out[i] = (uint8_t)(in[1 + i] + (in[0] == 1 && i >= r->channels ? out[i - r->channels] : 0));
    }
    return r->pixels != NULL;
}

static void png_read_free(png_read *r)
{
    free(r->pixels);
    free(r->filtered);
}

/* Encodes, then checks both readers give the input back. Returns the file (caller frees). */
static fc_buf encode_and_check(const uint8_t *px, uint32_t w, uint32_t h, uint32_t ch, uint32_t level,
                               unsigned threads)
{
    fc_png_rows rows = {px, w, h, ch, 0};
    fc_buf out;
    fc_buf_init(&out);
    fc_error err;
    fc_code code = fc_png_encode(&rows, level, threads, &out, &err);
    CHECK_MSG(code == FC_OK, "%ux%ux%u level %u threads %u: %s", w, h, ch, level, threads, err.message);
    if (code != FC_OK)
        return out;
    size_t n = (size_t)w * h * ch;
    png_read r;
    if (read_png(&out, level == 0 ? 0 : 1, &r)) {
        CHECK(r.width == w && r.height == h && r.channels == ch);
        CHECK_MSG(r.width == w && r.height == h && r.channels == ch && memcmp(r.pixels, px, n) == 0,
                  "%ux%ux%u level %u: own reader's pixels differ", w, h, ch, level);
    }
    png_read_free(&r);
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(out.data, out.len, "png", 0, &dec, &err), FC_OK);
    CHECK_MSG(dec.pixels && dec.width == w && dec.height == h && dec.channels == ch && memcmp(dec.pixels, px, n) == 0,
              "%ux%ux%u level %u: OpenImageIO's pixels differ (%ux%ux%u)", w, h, ch, level, dec.width, dec.height,
              dec.channels);
    fc_decoded_image_free(&dec);
    return out;
}

/* Sizes that split unevenly (1023x769 RGB: 42 rows per strip, 19 strips, the
 * last short), smaller than a strip, and a full-HD frame; every thread count
 * writes the same bytes. */
static void test_sizes_and_thread_counts(void)
{
    static const struct { uint32_t w, h, ch; } cases[] = {
        {1, 1, 4}, {1, 1, 3}, {1, 1, 1}, {7, 3, 4}, {7, 3, 3}, {1023, 769, 3}, {1023, 769, 4}, {1920, 1080, 4},
        {1920, 1080, 3}, {1, 40000, 4}, {333, 1000, 1},
    };
    static const unsigned threads[] = {1, 3, 8, 0};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        uint8_t *px = make_pixels(cases[c].w, cases[c].h, cases[c].ch, (uint32_t)c, 0);
        fc_buf first = encode_and_check(px, cases[c].w, cases[c].h, cases[c].ch, 4, threads[0]);
        for (size_t t = 1; t < sizeof threads / sizeof threads[0]; t++) {
            fc_buf again = encode_and_check(px, cases[c].w, cases[c].h, cases[c].ch, 4, threads[t]);
            CHECK_MSG(again.len == first.len && memcmp(again.data, first.data, first.len) == 0,
                      "%ux%ux%u: %u threads wrote other bytes than 1 (%zu vs %zu)", cases[c].w, cases[c].h,
                      cases[c].ch, threads[t], again.len, first.len);
            fc_buf_free(&again);
        }
        fc_buf_free(&first);
        free(px);
    }
}

/* Rows longer than a strip (128 KiB): one row per strip. */
static void test_rows_longer_than_a_strip(void)
{
    uint8_t *px = make_pixels(40000, 5, 4, 7, 0);
    fc_buf out = encode_and_check(px, 40000, 5, 4, 6, 3);
    png_read r;
    if (read_png(&out, 1, &r))
        CHECK_MSG(strcmp(r.chunks, "HFDDDDDE") == 0, "chunks %s: one IDAT per row expected", r.chunks);
    png_read_free(&r);
    fc_buf_free(&out);
    free(px);
}

/* Metadata as OpenImageIO's writer left it: IHDR, oFFs, the IDATs, IEND;
 * nothing else (no gAMA, sRGB or text). */
static void test_chunk_sequence(void)
{
    uint8_t *px = make_pixels(1024, 768, 4, 3, 0);
    fc_buf out = encode_and_check(px, 1024, 768, 4, 4, 2);
    png_read r;
    if (read_png(&out, 1, &r)) {
        /* 1024 RGBA: 4097 filtered bytes a row, 31 rows per strip, 25 strips. */
        char want[64] = "HF";
        memset(want + 2, 'D', 25);
        want[27] = 'E';
        CHECK_MSG(strcmp(r.chunks, want) == 0, "chunks %s, expected %s", r.chunks, want);
    }
    png_read_free(&r);
    fc_buf_free(&out);
    free(px);
}

/* The dictionary each strip starts with keeps the file as small as one
 * zlib stream of the same filtered rows at the same level would be. */
static void test_strips_compress_like_one_stream(void)
{
    uint8_t *px = make_pixels(1024, 768, 4, 11, 0);
    for (uint32_t level = 1; level <= 9; level += 4) {
        fc_buf out = encode_and_check(px, 1024, 768, 4, level, 0);
        png_read r;
        if (read_png(&out, 1, &r)) {
            uLongf one = compressBound(r.filtered_len);
            uint8_t *stream = malloc(one);
            CHECK_CODE(compress2(stream, &one, r.filtered, r.filtered_len, (int)level), Z_OK);
            printf("level %u: %zu bytes of zlib stream in strips, %lu as one stream\n", level, r.zlib_len,
                   (unsigned long)one);
            CHECK_MSG(r.zlib_len <= one + one / 200, "level %u: %zu bytes in strips, one stream %lu", level,
                      r.zlib_len, (unsigned long)one);
            free(stream);
        }
        png_read_free(&r);
        fc_buf_free(&out);
    }
    free(px);
}

/* Level 0 stores; higher levels shrink the file (the daemon's --png-compression). */
static void test_levels(void)
{
    uint8_t *px = make_pixels(300, 500, 4, 5, 0);
    size_t sizes[10];
    for (uint32_t level = 0; level <= 9; level++) {
        fc_buf out = encode_and_check(px, 300, 500, 4, level, 0);
        sizes[level] = out.len;
        fc_buf_free(&out);
    }
    CHECK_MSG(sizes[0] >= 300u * 500 * 4, "level 0: %zu bytes", sizes[0]);
    CHECK_MSG(sizes[1] < sizes[0] / 2, "level 1: %zu, level 0: %zu", sizes[1], sizes[0]);
    CHECK_MSG(sizes[9] < sizes[1], "level 9: %zu, level 1: %zu", sizes[9], sizes[1]);
    free(px);
}

/* Random sizes, channels, levels and thread counts; noise or gradients. */
static void test_random_shapes(void)
{
    static const uint32_t channels[] = {1, 3, 4};
    uint32_t state = 12345;
    for (int i = 0; i < 40; i++) {
        state = state * 1664525u + 1013904223u;
        uint32_t w = 1 + (state >> 8) % 333;
        state = state * 1664525u + 1013904223u;
        uint32_t h = 1 + (state >> 8) % 700;
        uint32_t ch = channels[(state >> 4) % 3];
        uint32_t level = (state >> 12) % 10;
        unsigned threads = (state >> 20) % 6;
        uint8_t *px = make_pixels(w, h, ch, (uint32_t)i, i % 3 == 0);
        fc_buf out = encode_and_check(px, w, h, ch, level, threads);
        fc_buf_free(&out);
        free(px);
    }
}

/* What PNG cannot hold is refused, and nothing is appended. */
static void test_refusals(void)
{
    uint8_t px[16] = {0};
    fc_buf out;
    fc_buf_init(&out);
    CHECK(fc_buf_reserve(&out, 3));
    out.len = 3;
    fc_error err;
    fc_png_rows two = {px, 2, 2, 2, 0}, empty = {px, 0, 2, 4, 0}, none = {NULL, 2, 2, 4, 0},
                huge = {px, 0x80000000u, 1, 1, 0};
    fc_png_rows ok = {px, 2, 2, 4, 0};
    CHECK_CODE(fc_png_encode(&two, 4, 0, &out, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_png_encode(&empty, 4, 0, &out, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_png_encode(&none, 4, 0, &out, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_png_encode(&huge, 4, 0, &out, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_png_encode(&ok, 10, 0, &out, &err), FC_ERR_USAGE);
    CHECK(out.len == 3);
    fc_buf_free(&out);
}

/* fc_encode_image's PNG goes through this writer: F32 colour converted, the level honoured. */
static void test_through_fc_encode_image(void)
{
    uint8_t *px = make_pixels(257, 129, 4, 9, 0);
    fc_image img = {257, 129, 4, FC_PIXEL_U8, px, 0};
    fc_buf via, direct;
    fc_buf_init(&via);
    fc_error err;
    CHECK_CODE(fc_encode_image_png_level(&img, FC_FORMAT_PNG, 0, 7, &via, &err), FC_OK);
    direct = encode_and_check(px, 257, 129, 4, 7, 1);
    CHECK_MSG(via.len == direct.len && memcmp(via.data, direct.data, via.len) == 0,
              "fc_encode_image wrote %zu bytes, fc_png_encode %zu", via.len, direct.len);
    fc_buf_free(&via);
    fc_buf_free(&direct);
    free(px);
}

/* An RGBA image whose every pixel is opaque (every colour image fluidcastd
 * renders) is written as RGB, its alpha read past in place: IHDR's colour
 * type 2, the bytes of the same RGB rows packed, and the input's RGB decoded
 * back; one translucent pixel
 * keeps RGBA (colour type 6). Pixel strides the rows cannot have are refused. */
static void test_opaque_rgba_written_as_rgb(void)
{
    enum { W = 301, H = 77, IHDR_COLOUR_TYPE = 8 + 8 + 9 };
    uint8_t *px = make_pixels(W, H, 4, 11, 0), *rgb = make_pixels(W, H, 3, 11, 0);
    for (size_t i = 0; px && rgb && i < (size_t)W * H; i++) {
        px[4 * i + 3] = 255;
        memcpy(rgb + 3 * i, px + 4 * i, 3);
    }
    fc_image img = {W, H, 4, FC_PIXEL_U8, px, 0};
    fc_buf via;
    fc_buf_init(&via);
    fc_error err;
    CHECK_CODE(fc_encode_image_png_level(&img, FC_FORMAT_PNG, 0, 2, &via, &err), FC_OK);
    fc_buf packed = encode_and_check(rgb, W, H, 3, 2, 0);
    CHECK(via.len > IHDR_COLOUR_TYPE && via.data[IHDR_COLOUR_TYPE] == 2);
    CHECK_MSG(via.len == packed.len && memcmp(via.data, packed.data, via.len) == 0,
              "opaque RGBA: %zu bytes, the packed RGB rows %zu", via.len, packed.len);
    fc_decoded_image dec;
    CHECK_CODE(fc_decode_image(via.data, via.len, "png", 0, &dec, &err), FC_OK);
    CHECK(dec.pixels && dec.channels == 3 && memcmp(dec.pixels, rgb, (size_t)W * H * 3) == 0);
    fc_decoded_image_free(&dec);

    px[4 * (W * H / 2) + 3] = 254;
    fc_buf translucent;
    fc_buf_init(&translucent);
    CHECK_CODE(fc_encode_image_png_level(&img, FC_FORMAT_PNG, 0, 2, &translucent, &err), FC_OK);
    CHECK(translucent.len > IHDR_COLOUR_TYPE && translucent.data[IHDR_COLOUR_TYPE] == 6);

    fc_png_rows narrow = {px, W, H, 4, 3}, wide = {px, W, H, 3, 5};
    fc_buf refused;
    fc_buf_init(&refused);
    CHECK_CODE(fc_png_encode(&narrow, 2, 0, &refused, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_png_encode(&wide, 2, 0, &refused, &err), FC_ERR_USAGE);
    CHECK(refused.len == 0);
    fc_buf_free(&via);
    fc_buf_free(&packed);
    fc_buf_free(&translucent);
    fc_buf_free(&refused);
    free(px);
    free(rgb);
}

int main(void)
{
    test_sizes_and_thread_counts();
    test_rows_longer_than_a_strip();
    test_chunk_sequence();
    test_strips_compress_like_one_stream();
    test_levels();
    test_random_shapes();
    test_refusals();
    test_through_fc_encode_image();
    test_opaque_rgba_written_as_rgb();
    return test_result();
}
