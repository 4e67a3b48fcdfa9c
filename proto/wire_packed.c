/* wire_packed.c — FRAME_PACKED and CHUNK: a frame in a packed body, optionally
 * zstd-compressed and/or with positions quantised to 16 bits per axis inside
 * the frame's bounding box. */
#include "wire_session.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <zstd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "wire_frame_io.h"

#define QUANT_FIXED_SIZE 40u             /* count, attributes, reserved, lo[3], hi[3] */
#define QUANT_STEPS 65535.0
#define MAX_PARTICLE_BYTES 36u           /* position, density, velocity, id, radius */
#define INNER_FIXED_MAX 64u              /* the largest fixed part of an inner layout, rounded up */
#define ATTR_ALL FC_ATTR_ALL

double fc_quantize_error_bound(float lo, float hi)
{
    return ((double)hi - (double)lo) / QUANT_STEPS / 2.0;
}

/* ---- Quantised inner layout ---- */

static uint16_t quantize(float value, float lo, double extent)
{
    if (!(extent > 0.0))
        return 0;
    double q = nearbyint(((double)value - lo) / extent * QUANT_STEPS);
    return (uint16_t)(q < 0.0 ? 0.0 : q > QUANT_STEPS ? QUANT_STEPS : q);
}

static float dequantize(uint16_t q, float lo, double extent)
{
    return (float)((double)lo + (double)q * (extent / QUANT_STEPS));
}

static void put_quantized(fc_buf *b, const fc_frame *frame)
{
    float lo[3], hi[3];
    fc_frame_bounds(frame, lo, hi);
    size_t count = (size_t)frame->count;
    wire_put_u64(b, frame->count);
    wire_put_u32(b, fc_frame_attributes(frame));
    wire_put_u32(b, 0);
    wire_put_f32_array(b, lo, 3);
    wire_put_f32_array(b, hi, 3);
    for (size_t i = 0; i < 3 * count; i++) {
        int axis = (int)(i % 3);
        wire_put_u16(b, quantize(frame->positions[i], lo[axis], (double)hi[axis] - lo[axis]));
    }
    /* Keeps the float arrays that follow on 4-byte boundaries. */
    if ((3 * count) % 2)
        wire_put_u16(b, 0);
    if (frame->density)
        wire_put_f32_array(b, frame->density, count);
    if (frame->velocity)
        wire_put_f32_array(b, frame->velocity, 3 * count);
    if (frame->ids)
        wire_put_u32_array(b, frame->ids, count);
    /* Radii travel as they are, never quantised: a splat's size is not a position. */
    if (frame->radius)
        wire_put_f32_array(b, frame->radius, count);
}

/* Bytes per particle of the arrays after the positions. */
static uint64_t attribute_bytes(uint32_t attributes)
{
    return fc_frame_particle_bytes(attributes) - 3 * sizeof(float);
}

/* Checks the fixed part in the order PROTOCOL.md gives, before allocating. */
static void check_quantized_layout(wire_reader *r, uint64_t count, uint32_t attributes, uint32_t reserved,
                                   const float *lo, const float *hi, uint64_t max_particles)
{
    uint64_t per_particle = 6 + attribute_bytes(attributes);
    if (attributes & ~(uint32_t)ATTR_ALL)
        wire_fail(r, FC_ERR_MALFORMED, "unknown attribute bits 0x%x", attributes & ~(uint32_t)ATTR_ALL);
    else if (reserved != 0)
        wire_fail(r, FC_ERR_MALFORMED, "reserved field is %u, must be 0", reserved);
    else if (count == 0)
        wire_fail(r, FC_ERR_INVALID_VALUE, "a frame needs at least one particle");
    else if (count > max_particles)
        wire_fail(r, FC_ERR_LIMIT, "%llu particles exceed the limit of %llu", (unsigned long long)count,
                  (unsigned long long)max_particles);
    else if (count > wire_remaining(r) / per_particle ||
             count * per_particle + (count % 2) * 2 != wire_remaining(r))
        wire_fail(r, FC_ERR_MALFORMED, "%llu quantised particles do not match the %zu bytes that follow",
                  (unsigned long long)count, wire_remaining(r));
    for (int k = 0; k < 3 && r->code == FC_OK; k++)
        if (!isfinite(lo[k]) || !isfinite(hi[k]) || lo[k] > hi[k])
            wire_fail(r, FC_ERR_INVALID_VALUE, "bounding box axis %d [%g, %g] is not a finite range", k,
                      (double)lo[k], (double)hi[k]);
}

static void get_quantized_positions(wire_reader *r, fc_frame *frame, const float *lo, const float *hi)
{
    size_t values = 3 * (size_t)frame->count;
    const uint8_t *q = wire_get_bytes(r, 2 * values, "quantised positions");
    if (!q)
        return;
    for (size_t i = 0; i < values; i++) {
        int axis = (int)(i % 3);
        uint16_t v = (uint16_t)(q[2 * i] | q[2 * i + 1] << 8);
        frame->positions[i] = dequantize(v, lo[axis], (double)hi[axis] - lo[axis]);
    }
    if (values % 2)
        wire_get_bytes(r, 2, "padding");
}

/* The quantised layout dequantised into a block from src, the attributes copied after the positions. */
static fc_code view_quantized(const uint8_t *p, size_t n, uint64_t max_particles, const fc_block_source *src,
                              fc_frame_view *out, fc_error *err)
{
    float lo[3], hi[3];
    wire_reader r = wire_reader_start(p, n, "quantised frame", err);
    uint64_t count = wire_get_u64(&r, "count");
    uint32_t attributes = wire_get_u32(&r, "attributes");
    uint32_t reserved = wire_get_u32(&r, "reserved");
    wire_get_f32_array(&r, lo, 3, "bounding box low");
    wire_get_f32_array(&r, hi, 3, "bounding box high");
    if (r.code == FC_OK)
        check_quantized_layout(&r, count, attributes, reserved, lo, hi, max_particles);
    if (r.code != FC_OK)
        return r.code;
    size_t size = fc_frame_block_size(count, attributes);
    uint8_t *block = src->take(src->ctx, size);
    if (!block)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a frame of %llu particles", (unsigned long long)count);
    fc_frame frame;
    fc_frame_point_into_block(&frame, block, count, attributes);
    get_quantized_positions(&r, &frame, lo, hi);
    fc_code code = wire_get_frame_attributes(&r, &frame, err);
    if (code != FC_OK) {
        src->give(src->ctx, block, size);
        return code;
    }
    *out = (fc_frame_view){frame, block, size};
    return FC_OK;
}

/* ---- Packed body: encoding, reserved, raw_size, bytes ---- */

/* The inner layout (FRAME payload or quantised) into *inner. */
static fc_code build_inner(fc_buf *inner, const fc_frame *frame, uint32_t encoding, fc_error *err)
{
    if (!(encoding & FC_PACK_QUANTIZE16)) {
        /* A FRAME message minus its header is exactly the plain inner layout. */
        fc_code code = fc_wire_write_frame(inner, 0, frame, err);
        if (code == FC_OK) {
            memmove(inner->data, inner->data + FC_WIRE_HEADER_SIZE, inner->len - FC_WIRE_HEADER_SIZE);
            inner->len -= FC_WIRE_HEADER_SIZE;
        }
        return code;
    }
    if (!frame || frame->count == 0 || !frame->positions)
        return fc_error_set(err, FC_ERR_USAGE, "a frame needs at least one particle");
    /* Quantising needs finite bounds; a plain FRAME leaves this check to the server. */
    fc_error why;
    if (fc_frame_validate(frame, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "cannot quantise: %s", why.message);
    fc_code code = wire_check_length(QUANT_FIXED_SIZE + 2, frame->count, 6 + attribute_bytes(fc_frame_attributes(frame)),
                             "quantised frame", err);
    if (code != FC_OK)
        return code;
    put_quantized(inner, frame);
    return inner->failed ? fc_error_set(err, FC_ERR_NOMEM, "out of memory while quantising a frame") : FC_OK;
}

static fc_code compress_into(fc_buf *out, const fc_buf *inner, int level, fc_error *err)
{
    size_t bound = ZSTD_compressBound(inner->len);
    if (!fc_buf_reserve(out, bound))
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory while compressing a frame");
    size_t written = ZSTD_compress(out->data + out->len, bound, inner->data, inner->len, level);
    if (ZSTD_isError(written))
        return fc_error_set(err, FC_ERR_INTERNAL, "zstd: %s", ZSTD_getErrorName(written));
    out->len += written;
    return FC_OK;
}

static fc_code put_packed_body(fc_buf *out, const fc_frame *frame, uint32_t encoding, int level, fc_error *err)
{
    if (encoding & ~(uint32_t)FC_PACK_ALL)
        return fc_error_set(err, FC_ERR_USAGE, "unknown packing bits 0x%x", encoding & ~(uint32_t)FC_PACK_ALL);
    if (level == 0)
        level = FC_PACK_DEFAULT_ZSTD_LEVEL;
    if (level < ZSTD_minCLevel() || level > ZSTD_maxCLevel())
        return fc_error_set(err, FC_ERR_USAGE, "zstd level %d is outside %d..%d", level, ZSTD_minCLevel(),
                            ZSTD_maxCLevel());
    fc_buf inner;
    fc_buf_init(&inner);
    fc_code code = build_inner(&inner, frame, encoding, err);
    if (code == FC_OK) {
        wire_put_u32(out, encoding);
        wire_put_u32(out, 0);
        wire_put_u64(out, inner.len);
        if (encoding & FC_PACK_ZSTD)
            code = compress_into(out, &inner, level, err);
        else
            wire_put_bytes(out, inner.data, inner.len);
    }
    fc_buf_free(&inner);
    return code;
}

/* Sets the length of the message begun at `start` to what was appended since. */
static fc_code finish_message(fc_buf *out, size_t start, fc_code code, fc_error *err)
{
    if (code == FC_OK)
        code = wire_end_message(out, start, err);
    size_t payload = out->len - start - FC_WIRE_HEADER_SIZE;
    if (code == FC_OK && payload > UINT32_MAX)
        code = fc_error_set(err, FC_ERR_TOO_LARGE, "packed payload of %zu bytes exceeds 4 GiB", payload);
    if (code != FC_OK) {
        out->len = start;
        return code;
    }
    wire_store_le(out->data + start + 12, payload, 4);
    return FC_OK;
}

fc_code fc_wire_write_frame_packed(fc_buf *out, uint32_t request_id, const fc_frame *frame, uint32_t encoding,
                                   int zstd_level, fc_error *err)
{
    size_t start = wire_begin_message(out, FC_MSG_FRAME_PACKED, request_id, 0);
    fc_code code = put_packed_body(out, frame, encoding, zstd_level, err);
    return finish_message(out, start, code, err);
}

fc_code fc_wire_write_chunk(fc_buf *out, uint32_t request_id, const fc_chunk_header *h, const fc_frame *part,
                            uint32_t encoding, int zstd_level, fc_error *err)
{
    size_t start = wire_begin_message(out, FC_MSG_CHUNK, request_id, 0);
    wire_put_u64(out, h->frame_number);
    wire_put_u32(out, h->index);
    wire_put_u32(out, h->count);
    fc_code code = put_packed_body(out, part, encoding, zstd_level, err);
    return finish_message(out, start, code, err);
}

/* The largest inner layout max_particles allows, so a compressed body cannot
 * make the server allocate more than a plain frame of the limit would take. */
static uint64_t inner_size_limit(uint64_t max_particles)
{
    if (max_particles > (UINT64_MAX - INNER_FIXED_MAX) / MAX_PARTICLE_BYTES)
        return UINT64_MAX;
    return INNER_FIXED_MAX + max_particles * MAX_PARTICLE_BYTES;
}

/* Decompresses into a block of raw_size bytes from src. */
static fc_code decompress(const uint8_t *bytes, size_t n, uint64_t raw_size, const fc_block_source *src,
                          uint8_t **out, fc_error *err)
{
    unsigned long long declared = ZSTD_getFrameContentSize(bytes, n);
    if (declared == ZSTD_CONTENTSIZE_ERROR)
        return fc_error_set(err, FC_ERR_MALFORMED, "packed body: not a zstd frame");
    /* Exactly one frame: ZSTD_decompress would go on through frames after it. */
    size_t frame_size = ZSTD_findFrameCompressedSize(bytes, n);
    if (ZSTD_isError(frame_size) || frame_size != n)
        return fc_error_set(err, FC_ERR_MALFORMED, "packed body: not exactly one zstd frame");
    if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != raw_size)
        return fc_error_set(err, FC_ERR_MALFORMED, "packed body: zstd frame holds %llu bytes, raw_size says %llu",
                            declared, (unsigned long long)raw_size);
    if (raw_size > SIZE_MAX)
        return fc_error_set(err, FC_ERR_LIMIT, "packed body: %llu bytes do not fit in memory",
                            (unsigned long long)raw_size);
    uint8_t *raw = src->take(src->ctx, (size_t)raw_size);
    if (!raw)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %llu-byte frame", (unsigned long long)raw_size);
    size_t got = ZSTD_decompress(raw, (size_t)raw_size, bytes, n);
    if (ZSTD_isError(got) || got != raw_size) {
        src->give(src->ctx, raw, (size_t)raw_size);
        return fc_error_set(err, FC_ERR_MALFORMED, "packed body: zstd: %s",
                            ZSTD_isError(got) ? ZSTD_getErrorName(got) : "fewer bytes than raw_size");
    }
    *out = raw;
    return FC_OK;
}

static fc_code view_inner(uint8_t *inner, size_t n, uint32_t encoding, uint64_t max_particles,
                          const fc_block_source *src, fc_frame_view *out, fc_error *err)
{
    if (encoding & FC_PACK_QUANTIZE16)
        return view_quantized(inner, n, max_particles, src, out, err);
    out->block = NULL;
    out->block_size = 0;
    return fc_wire_view_frame(inner, n, max_particles, &out->frame, err);
}

/* A plain inner layout stays where it is; a compressed one is decompressed
 * into a block, which then holds the frame unless quantised values need another. */
static fc_code view_packed_body(wire_reader *r, uint8_t *payload, uint32_t allowed, uint64_t max_particles,
                                const fc_block_source *src, fc_frame_view *out)
{
    uint32_t encoding = wire_get_u32(r, "encoding");
    uint32_t reserved = wire_get_u32(r, "reserved");
    uint64_t raw_size = wire_get_u64(r, "raw_size");
    if (r->code != FC_OK)
        return r->code;
    if (encoding & ~(uint32_t)FC_PACK_ALL)
        wire_fail(r, FC_ERR_MALFORMED, "unknown encoding bits 0x%x", encoding & ~(uint32_t)FC_PACK_ALL);
    else if (reserved != 0)
        wire_fail(r, FC_ERR_MALFORMED, "reserved field is %u, must be 0", reserved);
    else if (encoding & ~allowed)
        wire_fail(r, FC_ERR_BAD_STATE, "encoding 0x%x was not negotiated in HELLO/WELCOME", encoding & ~allowed);
    else if (!(encoding & FC_PACK_ZSTD) && raw_size != wire_remaining(r))
        wire_fail(r, FC_ERR_MALFORMED, "raw_size %llu but %zu bytes follow", (unsigned long long)raw_size,
                  wire_remaining(r));
    else if (raw_size > inner_size_limit(max_particles))
        wire_fail(r, FC_ERR_LIMIT, "raw_size %llu exceeds what %llu particles take", (unsigned long long)raw_size,
                  (unsigned long long)max_particles);
    if (r->code != FC_OK)
        return r->code;
    size_t n = wire_remaining(r);
    uint8_t *body = payload + r->pos;
    if (!(encoding & FC_PACK_ZSTD))
        return view_inner(body, n, encoding, max_particles, src, out, r->err);
    uint8_t *raw = NULL;
    fc_code code = decompress(body, n, raw_size, src, &raw, r->err);
    if (code != FC_OK)
        return code;
    fc_frame_view inner;
    code = view_inner(raw, (size_t)raw_size, encoding, max_particles, src, &inner, r->err);
    if (code == FC_OK && !inner.block) {
        inner.block = raw;
        inner.block_size = (size_t)raw_size;
    } else {
        src->give(src->ctx, raw, (size_t)raw_size);
    }
    if (code == FC_OK)
        *out = inner;
    return code;
}

fc_code fc_wire_view_frame_packed(uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                                  const fc_block_source *src, fc_frame_view *out, fc_error *err)
{
    wire_reader r = wire_reader_start(p, n, "FRAME_PACKED", err);
    return view_packed_body(&r, p, allowed_encoding, max_particles, src, out);
}

fc_code fc_wire_view_chunk(uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                           const fc_block_source *src, fc_chunk_header *h, fc_frame_view *part, fc_error *err)
{
    wire_reader r = wire_reader_start(p, n, "CHUNK", err);
    fc_chunk_header header;
    header.frame_number = wire_get_u64(&r, "frame_number");
    header.index = wire_get_u32(&r, "index");
    header.count = wire_get_u32(&r, "count");
    if (r.code != FC_OK)
        return r.code;
    fc_code code = view_packed_body(&r, p, allowed_encoding, max_particles, src, part);
    if (code == FC_OK)
        *h = header;
    return code;
}

/* ---- Copying readers (clients, tools): a private copy of the payload viewed, then owned arrays ---- */

static uint8_t *take_malloc(void *ctx, size_t size)
{
    (void)ctx;
    return malloc(size ? size : 1);
}

static void give_free(void *ctx, uint8_t *block, size_t size)
{
    (void)ctx;
    (void)size;
    free(block);
}

static const fc_block_source heap_blocks = {take_malloc, give_free, NULL};

/* Views a private copy of p with `view` (NULL h: FRAME_PACKED) and returns owned arrays. */
static fc_code read_copied(const uint8_t *p, size_t n, uint32_t allowed, uint64_t max_particles, fc_chunk_header *h,
                           fc_frame *frame, fc_error *err)
{
    uint8_t *copy = malloc(n ? n : 1);
    if (!copy)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %zu-byte payload", n);
    memcpy(copy, p, n);
    fc_frame_view view;
    fc_code code = h ? fc_wire_view_chunk(copy, n, allowed, max_particles, &heap_blocks, h, &view, err)
                     : fc_wire_view_frame_packed(copy, n, allowed, max_particles, &heap_blocks, &view, err);
    if (code == FC_OK) {
        code = wire_frame_from_view(&view.frame, frame, err);
        free(view.block);
    }
    free(copy);
    return code;
}

fc_code fc_wire_read_frame_packed(const uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                                  fc_frame *frame, fc_error *err)
{
    return read_copied(p, n, allowed_encoding, max_particles, NULL, frame, err);
}

fc_code fc_wire_read_chunk(const uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                           fc_chunk_header *h, fc_frame *part, fc_error *err)
{
    fc_chunk_header header;
    fc_code code = read_copied(p, n, allowed_encoding, max_particles, &header, part, err);
    if (code == FC_OK)
        *h = header;
    return code;
}
