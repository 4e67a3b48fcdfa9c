/* test_service_wire.c — the session, streaming and packed-upload codec
 * (wire_session.h) without a server: exact bytes where the layout is fixed,
 * round trips, every rejection with its code, zstd round trips bit for bit,
 * quantisation within its documented bound, and truncated or corrupted input
 * (built with AddressSanitizer, so a read past a buffer fails the test). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "test_util.h"
#include "wire_io.h"
#include "wire_session.h"

enum { BIG_LIMIT = 1 << 24 };

/* A message's payload: after the 16-byte header. */
static const uint8_t *payload_of(const fc_buf *b)
{
    return b->data + FC_WIRE_HEADER_SIZE;
}

static size_t payload_len(const fc_buf *b)
{
    return b->len - FC_WIRE_HEADER_SIZE;
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t le64(const uint8_t *p)
{
    return (uint64_t)le32(p) | (uint64_t)le32(p + 4) << 32;
}

/* ---- Session messages ---- */

static void test_publish_bytes(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_publish(&b, 5, "ab", &err), FC_OK);
    const uint8_t expected[] = {'F', 'C', 'S', 'T', 16, 0, 0, 0, 5, 0, 0, 0, 4, 0, 0, 0, 2, 0, 'a', 'b'};
    CHECK(b.len == sizeof expected && memcmp(b.data, expected, sizeof expected) == 0);
    char name[FC_SESSION_NAME_MAX + 1];
    CHECK_CODE(fc_wire_read_publish(payload_of(&b), payload_len(&b), name, &err), FC_OK);
    CHECK(strcmp(name, "ab") == 0);
    /* Writers refuse names the readers would refuse. */
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_publish(&b, 5, "", &err), FC_ERR_USAGE);
    char long_name[FC_SESSION_NAME_MAX + 2];
    memset(long_name, 'n', sizeof long_name - 1);
    long_name[sizeof long_name - 1] = '\0';
    CHECK_CODE(fc_wire_write_publish(&b, 5, long_name, &err), FC_ERR_USAGE);
    CHECK(b.len == 0);
    fc_buf_free(&b);
}

static void test_name_rejections(void)
{
    char name[FC_SESSION_NAME_MAX + 1];
    fc_error err;
    const uint8_t empty[] = {0, 0};
    CHECK_CODE(fc_wire_read_publish(empty, sizeof empty, name, &err), FC_ERR_INVALID_VALUE);
    uint8_t long_name[2 + 65];
    long_name[0] = 65;
    long_name[1] = 0;
    memset(long_name + 2, 'x', 65);
    CHECK_CODE(fc_wire_read_publish(long_name, sizeof long_name, name, &err), FC_ERR_INVALID_VALUE);
    long_name[0] = 64;   /* 64 bytes is the longest name, then one byte too many */
    CHECK_CODE(fc_wire_read_publish(long_name, sizeof long_name, name, &err), FC_ERR_MALFORMED);
    CHECK_CODE(fc_wire_read_publish(long_name, sizeof long_name - 1, name, &err), FC_OK);
    CHECK(strlen(name) == 64);
    const uint8_t nul[] = {3, 0, 'a', 0, 'b'};
    CHECK_CODE(fc_wire_read_publish(nul, sizeof nul, name, &err), FC_ERR_MALFORMED);
    const uint8_t short_name[] = {3, 0, 'a', 'b'};
    CHECK_CODE(fc_wire_read_publish(short_name, sizeof short_name, name, &err), FC_ERR_MALFORMED);
}

static void test_subscribe(void)
{
    fc_subscribe in = {.request = {FC_FORMAT_JPEG, 75, FC_AOV_COLOR}, .width = 320, .height = 200, .name = "dam"};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_subscribe(&b, 9, &in, &err), FC_OK);
    const uint8_t *p = payload_of(&b);
    CHECK(payload_len(&b) == 22 + 3);
    CHECK(le32(p) == FC_FORMAT_JPEG && le32(p + 4) == 75 && le32(p + 8) == FC_AOV_COLOR);
    CHECK(le32(p + 12) == 320 && le32(p + 16) == 200 && p[20] == 3 && memcmp(p + 22, "dam", 3) == 0);
    fc_subscribe out;
    CHECK_CODE(fc_wire_read_subscribe(p, payload_len(&b), &out, &err), FC_OK);
    CHECK(out.request.format == FC_FORMAT_JPEG && out.request.quality == 75 && out.width == 320 &&
          out.height == 200 && strcmp(out.name, "dam") == 0);

    /* RENDER's rules for the format, and a size given whole or not at all. */
    uint8_t bad[25];
    memcpy(bad, p, sizeof bad);
    wire_store_le(bad, 9, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_ERR_INVALID_VALUE);
    memcpy(bad, p, sizeof bad);
    wire_store_le(bad + 8, FC_AOV_DEPTH, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_ERR_INVALID_VALUE);
    memcpy(bad, p, sizeof bad);
    wire_store_le(bad + 12, 0, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_ERR_INVALID_VALUE);
    wire_store_le(bad + 16, 0, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_OK);
    CHECK(out.width == 0 && out.height == 0);
    CHECK_CODE(fc_wire_read_subscribe(p, 24, &out, &err), FC_ERR_MALFORMED);
    /* H.264 (4:2:0) needs an even size; 0 x 0 is the even default. */
    memcpy(bad, p, sizeof bad);
    wire_store_le(bad, FC_FORMAT_H264, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_OK);
    wire_store_le(bad + 12, 321, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_ERR_INVALID_VALUE);
    wire_store_le(bad + 12, 320, 4);
    wire_store_le(bad + 16, 201, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_ERR_INVALID_VALUE);
    wire_store_le(bad + 12, 0, 4);
    wire_store_le(bad + 16, 0, 4);
    CHECK_CODE(fc_wire_read_subscribe(bad, sizeof bad, &out, &err), FC_OK);
    CHECK(out.request.format == FC_FORMAT_H264);
    fc_buf_free(&b);
}

static void test_session_state_and_list(void)
{
    fc_session_info infos[2] = {{"one", 2, 5, 100, 99}, {"two", 0, 1, 0, 0}};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_session_state(&b, 3, &infos[0], &err), FC_OK);
    const uint8_t *p = payload_of(&b);
    CHECK(payload_len(&b) == 26 + 3);
    CHECK(le32(p) == 2 && le32(p + 4) == 5 && le64(p + 8) == 100 && le64(p + 16) == 99);
    fc_session_info state;
    CHECK_CODE(fc_wire_read_session_state(p, payload_len(&b), &state, &err), FC_OK);
    CHECK(strcmp(state.name, "one") == 0 && state.producers == 2 && state.viewers == 5 && state.frames == 100 &&
          state.last_frame == 99);

    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_session_list(&b, 4, infos, 2, &err), FC_OK);
    fc_session_info *list = NULL;
    uint32_t count = 0;
    CHECK_CODE(fc_wire_read_session_list(payload_of(&b), payload_len(&b), &list, &count, &err), FC_OK);
    CHECK(count == 2 && list && strcmp(list[1].name, "two") == 0 && list[1].viewers == 1);
    free(list);
    /* A count the payload cannot hold is refused before anything is allocated. */
    uint8_t huge[4 + 29];
    memcpy(huge, payload_of(&b), sizeof huge);
    wire_store_le(huge, 0x10000000u, 4);
    CHECK_CODE(fc_wire_read_session_list(huge, sizeof huge, &list, &count, &err), FC_ERR_MALFORMED);
    CHECK(list == NULL && count == 0);
    const uint8_t none[4] = {0};
    CHECK_CODE(fc_wire_read_session_list(none, sizeof none, &list, &count, &err), FC_OK);
    CHECK(count == 0);
    free(list);
    CHECK_CODE(fc_wire_read_list_sessions(none, 1, &err), FC_ERR_MALFORMED);
    fc_buf_free(&b);
}

static void test_session_end(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_session_leave(&b, 8, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE && b.data[4] == 19);
    CHECK_CODE(fc_wire_read_session_leave(NULL, 0, &err), FC_OK);
    CHECK_CODE(fc_wire_read_session_leave((const uint8_t *)"x", 1, &err), FC_ERR_MALFORMED);
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_session_end(&b, 8, "dam", &err), FC_OK);
    char name[FC_SESSION_NAME_MAX + 1];
    CHECK_CODE(fc_wire_read_session_end(payload_of(&b), payload_len(&b), name, &err), FC_OK);
    CHECK(strcmp(name, "dam") == 0);
    fc_buf_free(&b);
}

static void test_stream_image(void)
{
    const uint8_t pixels[] = {1, 2, 3, 4, 5, 6, 7, 8};
    fc_image_reply image = {.width = 2, .height = 1, .format = FC_FORMAT_RAW, .aov = FC_AOV_COLOR,
                            .data = pixels, .size = sizeof pixels};
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        image.stage_ms[s] = s == FC_STAGE_QUEUE ? 2.5f : -1.0f;
    fc_stream_tag tag = {.frame_number = 0x0102030405060708ull, .sequence = 42, .missed = 7,
                         .flags = FC_STREAM_REFRESH};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_stream_image(&b, 11, &tag, &image, &err), FC_OK);
    const uint8_t *p = payload_of(&b);
    /* The tag, then exactly an IMAGE payload: 28 bytes + one stage + the data. */
    CHECK(b.data[4] == 20 && le32(b.data + 8) == 11 && le32(b.data + 12) == payload_len(&b));
    CHECK(payload_len(&b) == 24 + 28 + 8 + sizeof pixels);
    CHECK(le64(p) == tag.frame_number && le64(p + 8) == 42 && le32(p + 16) == 7 && le32(p + 20) == 1);
    CHECK(le32(p + 24) == 2 && le32(p + 28) == 1 && le32(p + 40) == 1 && le32(p + 44) == FC_STAGE_QUEUE);
    fc_stream_tag tag_out;
    fc_image_reply image_out;
    CHECK_CODE(fc_wire_read_stream_image(p, payload_len(&b), &tag_out, &image_out, &err), FC_OK);
    CHECK(tag_out.frame_number == tag.frame_number && tag_out.sequence == 42 && tag_out.missed == 7 &&
          tag_out.flags == FC_STREAM_REFRESH);
    CHECK(image_out.size == sizeof pixels && memcmp(image_out.data, pixels, sizeof pixels) == 0);
    CHECK(image_out.stage_ms[FC_STAGE_QUEUE] == 2.5f && image_out.stage_ms[FC_STAGE_TOTAL] < 0.0f);
    for (size_t n = 0; n < payload_len(&b); n++)
        CHECK_MSG(fc_wire_read_stream_image(p, n, &tag_out, &image_out, &err) == FC_ERR_MALFORMED,
                  "truncated to %zu bytes", n);
    fc_buf_free(&b);
}

/* ---- Packed frames ---- */

/* A lattice with every attribute: regular data that zstd compresses well. */
static fc_frame lattice(uint64_t count)
{
    fc_frame f;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&f, count, FC_ATTR_DENSITY | FC_ATTR_VELOCITY | FC_ATTR_IDS, &err), FC_OK);
    for (uint64_t i = 0; i < count; i++) {
        f.positions[3 * i] = (float)(i % 10) * 0.1f;
        f.positions[3 * i + 1] = (float)(i / 10 % 10) * 0.1f;
        f.positions[3 * i + 2] = (float)(i / 100) * 0.1f;
        f.density[i] = 1000.0f;
        f.velocity[3 * i] = 0.5f;
        f.velocity[3 * i + 1] = 0.0f;
        f.velocity[3 * i + 2] = -1.0f;
        f.ids[i] = (uint32_t)i;
    }
    return f;
}

static bool same_arrays(const fc_frame *a, const fc_frame *b, bool positions_too)
{
    size_t n = (size_t)a->count;
    return a->count == b->count && (!positions_too || memcmp(a->positions, b->positions, 12 * n) == 0) &&
           memcmp(a->density, b->density, 4 * n) == 0 && memcmp(a->velocity, b->velocity, 12 * n) == 0 &&
           memcmp(a->ids, b->ids, 4 * n) == 0;
}

static void test_zstd_is_lossless_and_smaller(void)
{
    fc_frame in = lattice(1000);
    fc_buf packed, plain;
    fc_buf_init(&packed);
    fc_buf_init(&plain);
    fc_error err;
    CHECK_CODE(fc_wire_write_frame_packed(&packed, 2, &in, FC_PACK_ZSTD, 0, &err), FC_OK);
    CHECK_CODE(fc_wire_write_frame(&plain, 2, &in, &err), FC_OK);
    CHECK(packed.data[4] == 22 && le32(packed.data + 12) == payload_len(&packed));
    CHECK(le32(payload_of(&packed)) == FC_PACK_ZSTD && le64(payload_of(&packed) + 8) == payload_len(&plain));
    CHECK_MSG(packed.len * 4 < plain.len, "zstd %zu bytes, plain %zu", packed.len, plain.len);
    fc_frame out = {0};
    CHECK_CODE(fc_wire_read_frame_packed(payload_of(&packed), payload_len(&packed), FC_PACK_ALL, BIG_LIMIT, &out,
                                         &err),
               FC_OK);
    CHECK(same_arrays(&in, &out, true));
    fc_frame_free(&out);
    /* Not negotiated: refused, not guessed at. */
    CHECK_CODE(fc_wire_read_frame_packed(payload_of(&packed), payload_len(&packed), FC_PACK_QUANTIZE16, BIG_LIMIT,
                                         &out, &err),
               FC_ERR_BAD_STATE);
    /* raw_size beyond what the particle limit allows: LIMIT before decompressing. */
    CHECK_CODE(fc_wire_read_frame_packed(payload_of(&packed), payload_len(&packed), FC_PACK_ALL, 10, &out, &err),
               FC_ERR_LIMIT);
    fc_frame_free(&in);
    fc_buf_free(&packed);
    fc_buf_free(&plain);
}

static double max_quantisation_error(const fc_frame *in, const fc_frame *out, double bound[3])
{
    float lo[3], hi[3];
    fc_frame_bounds(in, lo, hi);
    double worst = 0.0;
    for (int k = 0; k < 3; k++)
        bound[k] = fc_quantize_error_bound(lo[k], hi[k]);
    for (uint64_t i = 0; i < in->count; i++)
        for (int k = 0; k < 3; k++) {
            double e = fabs((double)out->positions[3 * i + k] - in->positions[3 * i + k]);
            /* Allowed: the bound, plus the rounding of the decoded float. */
            double slack = bound[k] + nextafterf(fabsf(in->positions[3 * i + k]) + 1e-30f, INFINITY) -
                           fabsf(in->positions[3 * i + k]);
            if (e / slack > worst)
                worst = e / slack;
        }
    return worst;
}

static void test_quantisation_stays_within_bound(uint32_t encoding)
{
    fc_frame in = lattice(999);   /* odd: the u16 array is padded */
    uint32_t seed = 12345;
    for (uint64_t i = 0; i < 3 * in.count; i++) {
        seed = seed * 1664525u + 1013904223u;
        in.positions[i] = -3.0f + 7.5f * (float)(seed >> 8) / (float)(1u << 24);
    }
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_frame_packed(&b, 1, &in, encoding, 0, &err), FC_OK);
    if (!(encoding & FC_PACK_ZSTD))
        CHECK_MSG(payload_len(&b) == 16 + 40 + 6 * 999 + 2 + 20 * 999, "payload %zu", payload_len(&b));
    fc_frame out = {0};
    CHECK_CODE(fc_wire_read_frame_packed(payload_of(&b), payload_len(&b), encoding, BIG_LIMIT, &out, &err), FC_OK);
    double bound[3];
    if (out.count == in.count) {
        double worst = max_quantisation_error(&in, &out, bound);
        CHECK_MSG(worst <= 1.0, "error %.3f x the bound", worst);
        /* The bound is attained, not loose: some coordinate is off by more than half of it. */
        CHECK_MSG(worst > 0.5, "error only %.3f x the bound", worst);
        CHECK_NEAR(bound[0], 7.5 / 65535 / 2, 1e-6);
        CHECK(same_arrays(&in, &out, false));
    }
    fc_frame_free(&out);
    fc_frame_free(&in);
    fc_buf_free(&b);
}

/* Positions on the quantisation grid, and a flat axis, decode exactly. */
static void test_grid_positions_are_exact(void)
{
    fc_frame in;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&in, 4, 0, &err), FC_OK);
    const float grid = 1.0f / 1024.0f;   /* (hi - lo) / 65535 with lo 0, hi 65535/1024 */
    const float x[4] = {0.0f, 65535 * grid, 32768 * grid, 777 * grid};
    for (int i = 0; i < 4; i++) {
        in.positions[3 * i] = x[i];
        in.positions[3 * i + 1] = x[3 - i];
        in.positions[3 * i + 2] = 2.5f;
    }
    fc_buf b;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_frame_packed(&b, 1, &in, FC_PACK_QUANTIZE16, 0, &err), FC_OK);
    fc_frame out = {0};
    CHECK_CODE(fc_wire_read_frame_packed(payload_of(&b), payload_len(&b), FC_PACK_ALL, BIG_LIMIT, &out, &err),
               FC_OK);
    CHECK(out.count == 4 && memcmp(in.positions, out.positions, sizeof(float) * 12) == 0);
    CHECK(fc_quantize_error_bound(0.0f, 65535.0f) == 0.5);
    fc_frame_free(&out);
    fc_frame_free(&in);
    fc_buf_free(&b);
}

static void expect_packed(const uint8_t *p, size_t n, fc_code expected, const char *what)
{
    fc_frame out = {0};
    fc_error err;
    fc_code got = fc_wire_read_frame_packed(p, n, FC_PACK_ALL, 1000, &out, &err);
    CHECK_MSG(got == expected, "%s: got %d (%s), expected %d", what, (int)got, err.message, (int)expected);
    fc_frame_free(&out);
}

static void test_packed_rejections(void)
{
    fc_frame in = lattice(10);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_frame_packed(&b, 1, &in, FC_PACK_QUANTIZE16, 0, &err), FC_OK);
    size_t n = payload_len(&b);
    uint8_t *p = malloc(n);
    const uint8_t *good = payload_of(&b);
    memcpy(p, good, n);
    expect_packed(p, n, FC_OK, "valid");
    p[0] = 0x04;
    expect_packed(p, n, FC_ERR_MALFORMED, "unknown encoding bit");
    memcpy(p, good, n);
    p[4] = 1;
    expect_packed(p, n, FC_ERR_MALFORMED, "reserved");
    memcpy(p, good, n);
    wire_store_le(p + 8, n - 15, 8);
    expect_packed(p, n, FC_ERR_MALFORMED, "raw_size != bytes that follow");
    memcpy(p, good, n);
    wire_store_le(p + 16, 1001, 8);
    expect_packed(p, n, FC_ERR_LIMIT, "count above max_particles");
    memcpy(p, good, n);
    wire_store_le(p + 16 + 16, 0x7fc00000u, 4);   /* lo.x = NaN */
    expect_packed(p, n, FC_ERR_INVALID_VALUE, "NaN bounding box");
    memcpy(p, good, n);
    wire_store_le(p + 16 + 28, 0xbf800000u, 4);   /* hi.x = -1 < lo.x = 0 */
    expect_packed(p, n, FC_ERR_INVALID_VALUE, "inverted bounding box");
    memcpy(p, good, n);
    wire_store_le(p + n - 40 - 40, 0x7f800000u, 4);   /* a density of +Inf */
    expect_packed(p, n, FC_ERR_INVALID_VALUE, "infinite density");
    memcpy(p, good, n);
    expect_packed(p, n - 1, FC_ERR_MALFORMED, "one byte short");
    for (size_t len = 0; len < n; len++) {
        fc_frame out = {0};
        CHECK_MSG(fc_wire_read_frame_packed(good, len, FC_PACK_ALL, 1000, &out, &err) != FC_OK, "length %zu", len);
        fc_frame_free(&out);
    }
    free(p);
    fc_frame_free(&in);
    fc_buf_free(&b);
}

/* Every single-byte corruption of a compressed body is refused or decodes to
 * a valid frame; never a read out of bounds (AddressSanitizer). */
static void test_corrupted_zstd(void)
{
    fc_frame in = lattice(50);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_frame_packed(&b, 1, &in, FC_PACK_ZSTD | FC_PACK_QUANTIZE16, 0, &err), FC_OK);
    size_t n = payload_len(&b);
    uint8_t *p = malloc(n);
    int refused = 0;
    for (size_t i = 16; i < n; i++) {
        memcpy(p, payload_of(&b), n);
        p[i] ^= 0x5a;
        fc_frame out = {0};
        fc_code code = fc_wire_read_frame_packed(p, n, FC_PACK_ALL, BIG_LIMIT, &out, &err);
        refused += code != FC_OK;
        CHECK(code == FC_OK || out.count == 0);
        fc_frame_free(&out);
    }
    CHECK_MSG(refused > 0, "no corruption was noticed");
    memcpy(p, payload_of(&b), n);
    memset(p + 16, 0, 4);   /* no zstd magic */
    expect_packed(p, n, FC_ERR_MALFORMED, "not a zstd frame");
    free(p);
    fc_frame_free(&in);
    fc_buf_free(&b);
}

/* Radii (attribute bit 3) in every packed encoding: after the ids, never
 * quantised, bit for bit; a bad radius refused as in FRAME. */
static void test_packed_radius(void)
{
    enum { N = 9 }; /* odd: the quantised positions are padded */
    fc_frame in;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&in, N, FC_ATTR_IDS | FC_ATTR_RADIUS, &err), FC_OK);
    for (uint32_t i = 0; i < N; i++) {
        for (int k = 0; k < 3; k++)
            in.positions[3 * i + k] = 0.37f * (float)i - (float)k;
        in.ids[i] = 1000 + i;
        in.radius[i] = 0.0123456789f * (float)(i + 1) + 1e-7f * (float)i; /* off any 16-bit grid */
    }
    const uint32_t encodings[] = {0, FC_PACK_ZSTD, FC_PACK_QUANTIZE16, FC_PACK_ZSTD | FC_PACK_QUANTIZE16};
    for (size_t e = 0; e < sizeof encodings / sizeof encodings[0]; e++) {
        fc_buf b;
        fc_buf_init(&b);
        if (encodings[e] == 0) {
            /* The plain inner layout is the FRAME payload itself. */
            fc_buf plain;
            fc_buf_init(&plain);
            CHECK_CODE(fc_wire_write_frame(&plain, 1, &in, &err), FC_OK);
            fc_frame out = {0};
            CHECK_CODE(fc_wire_read_frame(payload_of(&plain), payload_len(&plain), N, &out, &err), FC_OK);
            CHECK(out.radius && memcmp(out.radius, in.radius, sizeof(float) * N) == 0);
            fc_frame_free(&out);
            fc_buf_free(&plain);
            fc_buf_free(&b);
            continue;
        }
        CHECK_CODE(fc_wire_write_frame_packed(&b, 1, &in, encodings[e], 0, &err), FC_OK);
        if (encodings[e] == FC_PACK_QUANTIZE16) {
            /* 16 packed + 40 fixed + 6 N + 2 padding + 4 N ids, then the radii as f32, exactly. */
            const uint8_t *p = payload_of(&b);
            size_t radii_at = 16 + 40 + 6 * N + 2 + 4 * N;
            CHECK_MSG(payload_len(&b) == radii_at + 4 * N, "payload %zu", payload_len(&b));
            CHECK(le32(p + 16 + 8) == (FC_ATTR_IDS | FC_ATTR_RADIUS));
            CHECK(payload_len(&b) == radii_at + 4 * N && memcmp(p + radii_at, in.radius, 4 * N) == 0);
        }
        fc_frame out = {0};
        CHECK_CODE(fc_wire_read_frame_packed(payload_of(&b), payload_len(&b), FC_PACK_ALL, BIG_LIMIT, &out, &err),
                   FC_OK);
        CHECK_MSG(out.radius && memcmp(out.radius, in.radius, sizeof(float) * N) == 0, "encoding %u",
                  encodings[e]);
        CHECK(out.ids && memcmp(out.ids, in.ids, sizeof(uint32_t) * N) == 0);
        fc_frame_free(&out);
        fc_buf_free(&b);
    }

    /* A negative radius in a quantised, compressed chunk: INVALID_VALUE naming the particle. */
    in.radius[4] = -2.0f;
    fc_buf b;
    fc_buf_init(&b);
    fc_chunk_header h = {.frame_number = 3, .index = 0, .count = 1};
    CHECK_CODE(fc_wire_write_chunk(&b, 6, &h, &in, FC_PACK_ZSTD | FC_PACK_QUANTIZE16, 0, &err), FC_ERR_USAGE);
    CHECK(strstr(err.message, "particle 4 has radius -2") != NULL);
    CHECK_CODE(fc_wire_write_chunk(&b, 6, &h, &in, FC_PACK_ZSTD, 0, &err), FC_OK);
    fc_chunk_header out_h;
    fc_frame out = {0};
    CHECK_CODE(fc_wire_read_chunk(payload_of(&b), payload_len(&b), FC_PACK_ALL, BIG_LIMIT, &out_h, &out, &err),
               FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "particle 4 has radius -2, outside (0, 1e6]") != NULL, "%s", err.message);
    CHECK(out.count == 0);
    fc_frame_free(&in);
    fc_buf_free(&b);
}

static void test_chunk(void)
{
    fc_frame part = lattice(7);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_chunk_header h = {.frame_number = 77, .index = 2, .count = 3};
    CHECK_CODE(fc_wire_write_chunk(&b, 6, &h, &part, FC_PACK_ZSTD, 5, &err), FC_OK);
    const uint8_t *p = payload_of(&b);
    CHECK(b.data[4] == 21 && le64(p) == 77 && le32(p + 8) == 2 && le32(p + 12) == 3 && le32(p + 16) == FC_PACK_ZSTD);
    fc_chunk_header out_h;
    fc_frame out = {0};
    CHECK_CODE(fc_wire_read_chunk(p, payload_len(&b), FC_PACK_ALL, BIG_LIMIT, &out_h, &out, &err), FC_OK);
    CHECK(out_h.frame_number == 77 && out_h.index == 2 && out_h.count == 3 && same_arrays(&part, &out, true));
    fc_frame_free(&out);
    CHECK_CODE(fc_wire_read_chunk(p, 15, FC_PACK_ALL, BIG_LIMIT, &out_h, &out, &err), FC_ERR_MALFORMED);
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_chunk(&b, 6, &h, &part, FC_PACK_ZSTD, 99, &err), FC_ERR_USAGE);
    CHECK(b.len == 0);
    fc_frame_free(&part);
    fc_buf_free(&b);
}

int main(void)
{
    test_publish_bytes();
    test_name_rejections();
    test_subscribe();
    test_session_state_and_list();
    test_session_end();
    test_stream_image();
    test_zstd_is_lossless_and_smaller();
    test_quantisation_stays_within_bound(FC_PACK_QUANTIZE16);
    test_quantisation_stays_within_bound(FC_PACK_QUANTIZE16 | FC_PACK_ZSTD);
    test_grid_positions_are_exact();
    test_packed_rejections();
    test_corrupted_zstd();
    test_chunk();
    test_packed_radius();
    return test_result();
}
