/* fuzz_packed.c — invariants of accepted packed bodies, checked against an
 * independent reading of the body: the fuzzer unpacks zstd itself and reads the
 * quantised layout's box and 16-bit values from the bytes.
 *
 * - an encoding that was not negotiated is refused with BAD_STATE;
 * - a compressed body is exactly one zstd frame of raw_size bytes, and the same
 *   inner layout sent uncompressed decodes to the identical frame;
 * - a plain inner layout is a FRAME payload, whose encoding is canonical;
 * - quantised positions are the spec's function of q and the bounding box;
 * - the decoded frame survives the encoder: exactly, or within the quantisation
 *   bound when quantised. */
#include "fuzz_packed.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <zstd.h>

#include "fc_frame.h"
#include "fuzz_check.h"
#include "wire_session.h"

#define BODY_FIXED_SIZE 16u        /* encoding, reserved, raw_size */
#define QUANT_BOUNDS_OFFSET 16u    /* lo[3], hi[3] follow count, attributes, reserved */
#define QUANT_POSITIONS_OFFSET 40u
#define QUANT_STEPS 65535.0

static float load_f32(const uint8_t *p)
{
    uint32_t bits = fuzz_load_u32(p);
    float value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

static bool same_array(const void *a, const void *b, size_t bytes)
{
    return a == NULL || b == NULL ? a == b : memcmp(a, b, bytes) == 0;
}

/* The arrays quantisation leaves alone, bit for bit (so NaN or -0 cannot hide a difference). */
static bool same_attributes(const fc_frame *a, const fc_frame *b)
{
    size_t n = (size_t)a->count;
    return a->count == b->count && same_array(a->density, b->density, 4 * n) &&
           same_array(a->velocity, b->velocity, 12 * n) && same_array(a->ids, b->ids, 4 * n) &&
           same_array(a->radius, b->radius, 4 * n);
}

static bool frames_identical(const fc_frame *a, const fc_frame *b)
{
    return same_attributes(a, b) && same_array(a->positions, b->positions, 12 * (size_t)a->count);
}

static fc_code read_body(const uint8_t *p, size_t n, uint32_t allowed, fc_frame *frame, fc_error *err)
{
    return fc_wire_read_frame_packed(p, n, allowed, FUZZ_MAX_PARTICLES, frame, err);
}

static void check_needs_negotiation(fuzz_payload body, uint32_t encoding)
{
    if (encoding == 0)
        return;
    fc_frame frame = {0};
    fc_error err = {FC_OK, ""};
    fc_code code = read_body(body.p, body.n, FC_PACK_ALL & ~encoding, &frame, &err);
    FUZZ_REQUIRE(code == FC_ERR_BAD_STATE, "encoding 0x%x not negotiated, yet code %d", encoding, (int)code);
    fuzz_require_reported(code, &err);
}

/* The inner layout (malloc'd, raw_size bytes), unpacked here with zstd when compressed. */
static uint8_t *unpack_inner(fuzz_payload body, uint32_t encoding, uint64_t raw_size)
{
    const uint8_t *data = body.p + BODY_FIXED_SIZE;
    size_t n = body.n - BODY_FIXED_SIZE;
    uint8_t *inner = malloc(raw_size > 0 ? (size_t)raw_size : 1);
    FUZZ_REQUIRE(inner != NULL, "no memory for a %llu-byte inner layout", (unsigned long long)raw_size);
    if (!(encoding & FC_PACK_ZSTD)) {
        FUZZ_REQUIRE(n == raw_size, "raw_size %llu but %zu bytes follow", (unsigned long long)raw_size, n);
        memcpy(inner, data, n);
        return inner;
    }
    size_t frame_size = ZSTD_findFrameCompressedSize(data, n);
    FUZZ_REQUIRE(!ZSTD_isError(frame_size) && frame_size == n, "the body is not exactly one zstd frame (%s)",
                 ZSTD_isError(frame_size) ? ZSTD_getErrorName(frame_size) : "bytes after the first frame");
    size_t got = ZSTD_decompress(inner, (size_t)raw_size, data, n);
    FUZZ_REQUIRE(!ZSTD_isError(got) && got == raw_size, "the zstd frame does not hold raw_size %llu bytes",
                 (unsigned long long)raw_size);
    return inner;
}

static void append_le(fc_buf *b, uint64_t value, size_t bytes)
{
    FUZZ_REQUIRE(fc_buf_reserve(b, bytes), "no memory for %zu bytes", bytes);
    for (size_t i = 0; i < bytes; i++)
        b->data[b->len++] = (uint8_t)(value >> (8 * i));
}

static void check_same_uncompressed(const uint8_t *inner, uint64_t raw_size, uint32_t encoding,
                                    const fc_frame *decoded)
{
    fc_buf body;
    fc_buf_init(&body);
    append_le(&body, encoding & ~(uint32_t)FC_PACK_ZSTD, 4);
    append_le(&body, 0, 4);
    append_le(&body, raw_size, 8);
    FUZZ_REQUIRE(fc_buf_reserve(&body, (size_t)raw_size), "no memory for an uncompressed body");
    memcpy(body.data + body.len, inner, (size_t)raw_size);
    body.len += (size_t)raw_size;
    fc_frame frame = {0};
    fc_error err = {FC_OK, ""};
    FUZZ_REQUIRE(read_body(body.data, body.len, FC_PACK_ALL, &frame, &err) == FC_OK,
                 "the inner layout sent uncompressed is refused: %s", err.message);
    FUZZ_REQUIRE(frames_identical(&frame, decoded), "the inner layout sent uncompressed decodes differently");
    fc_frame_free(&frame);
    fc_buf_free(&body);
}

static void check_plain_is_frame(const uint8_t *inner, uint64_t raw_size, const fc_frame *decoded)
{
    fc_error err = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_frame(&encoded, 0, decoded, &err) == FC_OK, "re-encoding failed: %s", err.message);
    fuzz_require_same_payload(&encoded, (fuzz_payload){inner, (size_t)raw_size});
    fc_buf_free(&encoded);
}

/* More than the rounding to float of a value in [lo, hi]: relative, but
 * absolute among the subnormals. */
static double float_rounding(float lo, float hi)
{
    return (fabs(lo) + fabs(hi)) * FLT_EPSILON + FLT_TRUE_MIN;
}

/* Each coordinate is the spec's lo + q (hi - lo) / 65535, up to float rounding
 * (so it may stray past hi by that rounding, never further). */
static void check_dequantized(const uint8_t *inner, const fc_frame *decoded)
{
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = load_f32(inner + QUANT_BOUNDS_OFFSET + 4 * k);
        hi[k] = load_f32(inner + QUANT_BOUNDS_OFFSET + 12 + 4 * k);
    }
    for (size_t i = 0; i < 3 * (size_t)decoded->count; i++) {
        int k = (int)(i % 3);
        const uint8_t *bytes = inner + QUANT_POSITIONS_OFFSET + 2 * i;
        unsigned q = (unsigned)bytes[0] | (unsigned)bytes[1] << 8;
        double expected = lo[k] + q * ((double)hi[k] - lo[k]) / QUANT_STEPS;
        double rounding = float_rounding(lo[k], hi[k]);
        FUZZ_REQUIRE(fabs(decoded->positions[i] - expected) <= rounding, "q %u on [%g, %g] decoded as %g, not %g", q,
                     (double)lo[k], (double)hi[k], (double)decoded->positions[i], expected);
    }
}

/* Requantising moves a coordinate by at most the bound of its axis over the
 * frame's own bounds, plus the rounding of the decoded value to float. */
static void check_within_quantization(const fc_frame *again, const fc_frame *decoded)
{
    float lo[3], hi[3];
    fc_frame_bounds(decoded, lo, hi);
    for (size_t i = 0; i < 3 * (size_t)decoded->count; i++) {
        int k = (int)(i % 3);
        double tolerance = fc_quantize_error_bound(lo[k], hi[k]) + float_rounding(lo[k], hi[k]);
        double moved = fabs((double)again->positions[i] - decoded->positions[i]);
        FUZZ_REQUIRE(moved <= tolerance, "requantised coordinate moved by %g, bound %g", moved, tolerance);
    }
}

/* Through the encoder (compressed, and quantised when the body was) and back. */
static void check_encoder_round_trip(uint32_t encoding, const fc_frame *decoded)
{
    uint32_t again_encoding = FC_PACK_ZSTD | (encoding & FC_PACK_QUANTIZE16);
    fc_error err = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_frame_packed(&encoded, 0, decoded, again_encoding, 1, &err) == FC_OK,
                 "re-encoding failed: %s", err.message);
    fc_frame again = {0};
    FUZZ_REQUIRE(read_body(encoded.data + FC_WIRE_HEADER_SIZE, encoded.len - FC_WIRE_HEADER_SIZE, FC_PACK_ALL,
                           &again, &err) == FC_OK,
                 "re-encoded body refused: %s", err.message);
    if (again_encoding & FC_PACK_QUANTIZE16) {
        FUZZ_REQUIRE(same_attributes(&again, decoded), "requantising changed the count or an attribute");
        check_within_quantization(&again, decoded);
    } else {
        FUZZ_REQUIRE(frames_identical(&again, decoded), "the frame changed in an encode/decode round trip");
    }
    fc_frame_free(&again);
    fc_buf_free(&encoded);
}

void fuzz_check_packed_body(fuzz_payload body, const fc_frame *decoded)
{
    fc_error err = {FC_OK, ""};
    FUZZ_REQUIRE(body.n >= BODY_FIXED_SIZE, "accepted a %zu-byte body", body.n);
    FUZZ_REQUIRE(decoded->count >= 1 && decoded->count <= FUZZ_MAX_PARTICLES, "%llu particles",
                 (unsigned long long)decoded->count);
    FUZZ_REQUIRE(fc_frame_validate(decoded, &err) == FC_OK, "decoded frame is invalid: %s", err.message);
    uint32_t encoding = fuzz_load_u32(body.p);
    uint64_t raw_size = fuzz_load_u64(body.p + 8);
    check_needs_negotiation(body, encoding);
    uint8_t *inner = unpack_inner(body, encoding, raw_size);
    if (encoding & FC_PACK_ZSTD)
        check_same_uncompressed(inner, raw_size, encoding, decoded);
    if (encoding & FC_PACK_QUANTIZE16)
        check_dequantized(inner, decoded);
    else
        check_plain_is_frame(inner, raw_size, decoded);
    free(inner);
    check_encoder_round_trip(encoding, decoded);
}
