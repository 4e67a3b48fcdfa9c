/* test_service_wire_view.c — the server's decoders that view frames instead of
 * copying them: FRAME and plain packed bodies decode in place (the arrays point
 * into the payload at the layout's offsets and hold the values sent, bit for
 * bit); compressed and quantised bodies decode into blocks from the caller's
 * source, taking exactly the blocks they need and giving back the temporary
 * ones and every block on failure; validation still names the first bad
 * particle; no truncation is read past or accepted. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "test_util.h"
#include "wire_session.h"

enum { N = 5 };

typedef struct counting_source {
    int takes, gives;
    size_t last_take;
} counting_source;

static uint8_t *counted_take(void *ctx, size_t size)
{
    counting_source *c = ctx;
    c->takes++;
    c->last_take = size;
    return malloc(size ? size : 1);
}

static void counted_give(void *ctx, uint8_t *block, size_t size)
{
    (void)size;
    ((counting_source *)ctx)->gives++;
    free(block);
}

/* Positions on the quantisation grid of their own bounds (0 and 1 per axis), so quantising is exact. */
static fc_frame sample_frame(void)
{
    fc_frame f;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&f, N, FC_ATTR_DENSITY | FC_ATTR_VELOCITY | FC_ATTR_IDS, &err), FC_OK);
    for (int i = 0; i < N; i++) {
        for (int k = 0; k < 3; k++) {
            f.positions[3 * i + k] = (float)((i + k) % 2);
            f.velocity[3 * i + k] = 0.25f * (float)(i - k);
        }
        f.density[i] = 1000.0f + (float)i;
        f.ids[i] = 7000u + (uint32_t)i;
    }
    return f;
}

/* The message's payload in a fresh (malloc-aligned) block, as the daemon receives it. */
static uint8_t *payload_copy(const fc_buf *b, size_t *n)
{
    *n = b->len - FC_WIRE_HEADER_SIZE;
    uint8_t *p = malloc(*n + 1);
    memcpy(p, b->data + FC_WIRE_HEADER_SIZE, *n);
    return p;
}

static void check_same_frame(const fc_frame *got, const fc_frame *want)
{
    CHECK(got->count == want->count);
    CHECK(memcmp(got->positions, want->positions, 3 * N * sizeof(float)) == 0);
    CHECK(got->density && memcmp(got->density, want->density, N * sizeof(float)) == 0);
    CHECK(got->velocity && memcmp(got->velocity, want->velocity, 3 * N * sizeof(float)) == 0);
    CHECK(got->ids && memcmp(got->ids, want->ids, N * sizeof(uint32_t)) == 0);
}

static void frame_is_viewed_in_place(void)
{
    fc_frame in = sample_frame();
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_frame(&b, 1, &in, &err), FC_OK);
    size_t n;
    uint8_t *p = payload_copy(&b, &n);
    fc_frame view;
    CHECK_CODE(fc_wire_view_frame(p, n, N, &view, &err), FC_OK);
    CHECK(view.positions == (float *)(p + 16));
    CHECK(view.density == (float *)(p + 16 + 12 * N));
    CHECK(view.velocity == (float *)(p + 16 + 16 * N));
    CHECK(view.ids == (uint32_t *)(p + 16 + 28 * N));
    check_same_frame(&view, &in);
    CHECK_CODE(fc_wire_view_frame(p, n, N - 1, &view, &err), FC_ERR_LIMIT);
    CHECK_CODE(fc_wire_view_frame(p, n - 4, N, &view, &err), FC_ERR_MALFORMED);

    /* Not 4-byte aligned: refused rather than read misaligned. */
    uint8_t *shifted = malloc(n + 1);
    memcpy(shifted + 1, p, n);
    CHECK_CODE(fc_wire_view_frame(shifted + 1, n, N, &view, &err), FC_ERR_USAGE);
    free(shifted);

    /* A NaN velocity of particle 3: validated in place, named by index. */
    float nan = NAN;
    memcpy(p + 16 + 16 * N + 4 * (3 * 3 + 1), &nan, 4);
    CHECK_CODE(fc_wire_view_frame(p, n, N, &view, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "particle 3 ") != NULL, "%s", err.message);
    free(p);
    fc_buf_free(&b);
    fc_frame_free(&in);
}

/* FRAME_PACKED with `encoding` viewed through a counting source. */
static fc_code view_packed(uint32_t encoding, const fc_frame *in, uint64_t max_particles, counting_source *count,
                           fc_frame_view *out, uint8_t **payload, size_t *n)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_code written = fc_wire_write_frame_packed(&b, 1, in, encoding, 0, &err);
    CHECK_MSG(written == FC_OK, "%s", err.message);
    *payload = payload_copy(&b, n);
    fc_buf_free(&b);
    fc_block_source src = {counted_take, counted_give, count};
    return fc_wire_view_frame_packed(*payload, *n, FC_PACK_ALL, max_particles, &src, out, &err);
}

static void packed_bodies_take_only_the_blocks_they_need(void)
{
    fc_frame in = sample_frame();
    uint8_t *p;
    size_t n;
    fc_frame_view view;
    size_t arrays = fc_frame_block_size(N, FC_ATTR_DENSITY | FC_ATTR_VELOCITY | FC_ATTR_IDS);
    CHECK(arrays == 32 * N);

    counting_source plain = {0};
    CHECK_CODE(view_packed(0, &in, N, &plain, &view, &p, &n), FC_OK);
    CHECK(plain.takes == 0 && plain.gives == 0 && view.block == NULL);
    /* encoding, reserved, raw_size, then FRAME's fixed part */
    CHECK(view.frame.positions == (float *)(p + 16 + 16));
    check_same_frame(&view.frame, &in);
    free(p);

    counting_source zstd = {0};
    CHECK_CODE(view_packed(FC_PACK_ZSTD, &in, N, &zstd, &view, &p, &n), FC_OK);
    CHECK(zstd.takes == 1 && zstd.gives == 0 && zstd.last_take == 16 + arrays);
    CHECK(view.block != NULL && view.block_size == 16 + arrays);
    CHECK(view.frame.positions == (float *)(view.block + 16));
    check_same_frame(&view.frame, &in);
    free(view.block);
    free(p);

    counting_source quantised = {0};
    CHECK_CODE(view_packed(FC_PACK_QUANTIZE16, &in, N, &quantised, &view, &p, &n), FC_OK);
    CHECK(quantised.takes == 1 && quantised.gives == 0 && quantised.last_take == arrays);
    CHECK(view.block_size == arrays && view.frame.positions == (float *)view.block);
    check_same_frame(&view.frame, &in);
    free(view.block);
    free(p);

    /* The decompressed quantised bytes are a temporary block: given back. */
    counting_source both = {0};
    CHECK_CODE(view_packed(FC_PACK_ZSTD | FC_PACK_QUANTIZE16, &in, N, &both, &view, &p, &n), FC_OK);
    CHECK(both.takes == 2 && both.gives == 1 && view.block_size == arrays);
    check_same_frame(&view.frame, &in);
    free(view.block);
    free(p);
    fc_frame_free(&in);
}

static void a_failed_decode_gives_every_block_back(void)
{
    fc_frame in = sample_frame();
    uint8_t *p;
    size_t n;
    fc_frame_view view;
    /* Refused after decompressing: the decompressed block goes back. */
    counting_source both = {0};
    CHECK_CODE(view_packed(FC_PACK_ZSTD | FC_PACK_QUANTIZE16, &in, N - 1, &both, &view, &p, &n), FC_ERR_LIMIT);
    CHECK_MSG(both.takes == 1 && both.gives == 1, "%d takes, %d gives", both.takes, both.gives);
    free(p);

    /* A quantised frame with an infinite density (patched in: writers refuse to quantise one). */
    counting_source quantised = {0};
    CHECK_CODE(view_packed(FC_PACK_QUANTIZE16, &in, N, &quantised, &view, &p, &n), FC_OK);
    free(view.block);
    /* packed header 16, quantised fixed part 40, positions 6 N + 2 bytes of padding, then densities */
    float inf = INFINITY;
    memcpy(p + 16 + 40 + 6 * N + 2 + 4 * 4, &inf, 4);
    fc_block_source src = {counted_take, counted_give, &quantised};
    fc_error err;
    CHECK_CODE(fc_wire_view_frame_packed(p, n, FC_PACK_ALL, N, &src, &view, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "particle 4 ") != NULL, "%s", err.message);
    CHECK_MSG(quantised.takes == 2 && quantised.gives == 1, "%d takes, %d gives", quantised.takes, quantised.gives);
    free(p);

    in.density[4] = INFINITY;
    counting_source zstd = {0};
    CHECK_CODE(view_packed(FC_PACK_ZSTD, &in, N, &zstd, &view, &p, &n), FC_ERR_INVALID_VALUE);
    CHECK_MSG(zstd.takes == 1 && zstd.gives == 1, "%d takes, %d gives", zstd.takes, zstd.gives);
    free(p);
    fc_frame_free(&in);
}

static void chunk_is_viewed_in_place(void)
{
    fc_frame in = sample_frame();
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_chunk_header h = {.frame_number = 42, .index = 1, .count = 3};
    CHECK_CODE(fc_wire_write_chunk(&b, 1, &h, &in, 0, 0, &err), FC_OK);
    size_t n;
    uint8_t *p = payload_copy(&b, &n);
    counting_source none = {0};
    fc_block_source src = {counted_take, counted_give, &none};
    fc_chunk_header got = {0};
    fc_frame_view view;
    CHECK_CODE(fc_wire_view_chunk(p, n, 0, N, &src, &got, &view, &err), FC_OK);
    CHECK(got.frame_number == 42 && got.index == 1 && got.count == 3);
    CHECK(none.takes == 0 && view.block == NULL);
    /* frame_number, index, count; encoding, reserved, raw_size; FRAME's fixed part */
    CHECK(view.frame.positions == (float *)(p + 16 + 16 + 16));
    check_same_frame(&view.frame, &in);
    free(p);
    fc_buf_free(&b);
    fc_frame_free(&in);
}

/* Every truncation of each message, in a block of exactly its length (so the
 * instrumented build faults on any read past it), is refused and takes no block for good. */
static void truncations_are_refused_in_place(void)
{
    fc_frame in = sample_frame();
    fc_error err;
    for (int kind = 0; kind < 4; kind++) {
        fc_buf b;
        fc_buf_init(&b);
        uint32_t encoding = kind == 1 ? FC_PACK_ZSTD : kind == 2 ? FC_PACK_QUANTIZE16 : 0;
        fc_code written = kind == 0 ? fc_wire_write_frame(&b, 1, &in, &err)
                        : kind == 3 ? fc_wire_write_chunk(&b, 1, &(fc_chunk_header){1, 0, 1}, &in, 0, 0, &err)
                                    : fc_wire_write_frame_packed(&b, 1, &in, encoding, 0, &err);
        CHECK_CODE(written, FC_OK);
        size_t full = b.len - FC_WIRE_HEADER_SIZE;
        for (size_t n = 0; n < full; n++) {
            uint8_t *p = malloc(n ? n : 1);
            memcpy(p, b.data + FC_WIRE_HEADER_SIZE, n);
            counting_source count = {0};
            fc_block_source src = {counted_take, counted_give, &count};
            fc_frame view;
            fc_frame_view packed;
            fc_chunk_header h;
            fc_code code = kind == 0 ? fc_wire_view_frame(p, n, N, &view, &err)
                         : kind == 3 ? fc_wire_view_chunk(p, n, FC_PACK_ALL, N, &src, &h, &packed, &err)
                                     : fc_wire_view_frame_packed(p, n, FC_PACK_ALL, N, &src, &packed, &err);
            CHECK_MSG(code != FC_OK, "kind %d: %zu of %zu bytes accepted", kind, n, full);
            CHECK_MSG(count.takes == count.gives, "kind %d, %zu bytes: %d takes, %d gives", kind, n, count.takes,
                      count.gives);
            free(p);
        }
        fc_buf_free(&b);
    }
    fc_frame_free(&in);
}

int main(void)
{
    frame_is_viewed_in_place();
    packed_bodies_take_only_the_blocks_they_need();
    a_failed_decode_gives_every_block_back();
    chunk_is_viewed_in_place();
    truncations_are_refused_in_place();
    return test_result();
}
