/* wire_io.c — little-endian primitives for the message codecs, and the
 * message header (framing) they start and end messages with. Below every
 * codec: it calls none of them. */
#include "wire_io.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"

/* Arrays are copied wholesale when the host already stores them little-endian. */
#define HOST_IS_LITTLE_ENDIAN WIRE_HOST_IS_LITTLE_ENDIAN

#define UTF8_CONTINUATION_MASK 0xC0u
#define UTF8_CONTINUATION_BITS 0x80u

void wire_store_le(uint8_t *out, uint64_t v, size_t bytes)
{
    for (size_t i = 0; i < bytes; i++)
        out[i] = (uint8_t)(v >> (8 * i));
}

static uint64_t load_le(const uint8_t *in, size_t bytes)
{
    uint64_t v = 0;
    for (size_t i = 0; i < bytes; i++)
        v |= (uint64_t)in[i] << (8 * i);
    return v;
}

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float bits_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* ---- Framing ---- */

void fc_wire_encode_header(uint8_t out[FC_WIRE_HEADER_SIZE], const fc_msg_header *h)
{
    memcpy(out, FC_WIRE_MAGIC, 4);
    wire_store_le(out + 4, h->type, 2);
    wire_store_le(out + 6, h->flags, 2);
    wire_store_le(out + 8, h->request_id, 4);
    wire_store_le(out + 12, h->length, 4);
}

fc_code fc_wire_decode_header(const uint8_t in[FC_WIRE_HEADER_SIZE], uint32_t max_payload,
                              fc_msg_header *h, fc_error *err)
{
    if (memcmp(in, FC_WIRE_MAGIC, 4) != 0)
        return fc_error_set(err, FC_ERR_BAD_MAGIC, "message starts with %02x %02x %02x %02x, not \"FCST\"",
                            in[0], in[1], in[2], in[3]);
    wire_reader r = wire_reader_start(in + 4, FC_WIRE_HEADER_SIZE - 4, "header", err);
    h->type = wire_get_u16(&r, "type");
    h->flags = wire_get_u16(&r, "flags");
    h->request_id = wire_get_u32(&r, "request_id");
    h->length = wire_get_u32(&r, "length");
    if (h->length > max_payload)
        return fc_error_set(err, FC_ERR_TOO_LARGE, "payload of %u bytes exceeds the limit of %u", h->length,
                            max_payload);
    if (h->flags != 0)
        return fc_error_set(err, FC_ERR_MALFORMED, "header flags 0x%04x must be 0 in protocol v1", h->flags);
    return FC_OK;
}

/* ---- Writing ---- */

void wire_put_bytes(fc_buf *b, const void *bytes, size_t n)
{
    if (n == 0 || !fc_buf_reserve(b, n))
        return;
    memcpy(b->data + b->len, bytes, n);
    b->len += n;
}

static void put_le(fc_buf *b, uint64_t v, size_t bytes)
{
    uint8_t tmp[8];
    wire_store_le(tmp, v, bytes);
    wire_put_bytes(b, tmp, bytes);
}

void wire_put_u16(fc_buf *b, uint16_t v) { put_le(b, v, 2); }
void wire_put_u32(fc_buf *b, uint32_t v) { put_le(b, v, 4); }
void wire_put_u64(fc_buf *b, uint64_t v) { put_le(b, v, 8); }
void wire_put_f32(fc_buf *b, float v) { put_le(b, float_bits(v), 4); }

/* float and uint32_t arrays share this: both are 4-byte words on the wire. */
static void put_words(fc_buf *b, const void *words, size_t count)
{
    if (count > SIZE_MAX / 4 || !fc_buf_reserve(b, count * 4))
        return;
    if (HOST_IS_LITTLE_ENDIAN) {
        wire_put_bytes(b, words, count * 4);
        return;
    }
    const uint8_t *src = words;
    for (size_t i = 0; i < count; i++) {
        uint32_t w;
        memcpy(&w, src + 4 * i, 4);
        put_le(b, w, 4);
    }
}

void wire_put_f32_array(fc_buf *b, const float *v, size_t count) { put_words(b, v, count); }
void wire_put_u32_array(fc_buf *b, const uint32_t *v, size_t count) { put_words(b, v, count); }

static size_t str_length(const char *text, size_t capacity)
{
    size_t len = strnlen(text, capacity);
    return len > UINT16_MAX ? UINT16_MAX : len;
}

size_t wire_str_size(const char *text, size_t capacity)
{
    return 2 + str_length(text, capacity);
}

void wire_put_str(fc_buf *b, const char *text, size_t capacity)
{
    size_t len = str_length(text, capacity);
    wire_put_u16(b, (uint16_t)len);
    wire_put_bytes(b, text, len);
}

size_t wire_begin_message_part(fc_buf *b, fc_msg_type type, uint32_t request_id, uint32_t length,
                               size_t part_bytes)
{
    size_t start = b->len;
    uint8_t header[FC_WIRE_HEADER_SIZE];
    fc_msg_header h = {.type = (uint16_t)type, .flags = 0, .request_id = request_id, .length = length};
    fc_wire_encode_header(header, &h);
    /* One reservation for all that goes into b, so large payloads are not regrown piecemeal. */
    if (fc_buf_reserve(b, FC_WIRE_HEADER_SIZE + part_bytes))
        wire_put_bytes(b, header, sizeof header);
    return start;
}

size_t wire_begin_message(fc_buf *b, fc_msg_type type, uint32_t request_id, uint32_t length)
{
    return wire_begin_message_part(b, type, request_id, length, length);
}

fc_code wire_end_message(fc_buf *b, size_t start, fc_error *err)
{
    if (!b->failed)
        return FC_OK;
    if (b->len > start)
        b->len = start;
    return fc_error_set(err, FC_ERR_NOMEM, "out of memory while encoding a message");
}

fc_code wire_write_empty(fc_buf *b, fc_msg_type type, uint32_t request_id, fc_error *err)
{
    size_t start = wire_begin_message(b, type, request_id, 0);
    return wire_end_message(b, start, err);
}

fc_code wire_check_length(uint64_t fixed, uint64_t count, uint64_t unit, const char *message, fc_error *err)
{
    if (count > (UINT32_MAX - fixed) / unit)
        return fc_error_set(err, FC_ERR_TOO_LARGE, "%s payload of %llu + %llu x %llu bytes exceeds 4 GiB", message,
                            (unsigned long long)fixed, (unsigned long long)count, (unsigned long long)unit);
    return FC_OK;
}

/* ---- Reading ---- */

wire_reader wire_reader_start(const uint8_t *p, size_t n, const char *message, fc_error *err)
{
    return (wire_reader){.p = p, .n = n, .pos = 0, .message = message, .err = err, .code = FC_OK};
}

size_t wire_remaining(const wire_reader *r)
{
    return r->n - r->pos;
}

void wire_fail(wire_reader *r, fc_code code, const char *fmt, ...)
{
    if (r->code != FC_OK)
        return;
    char reason[FC_ERROR_MESSAGE_MAX];
    va_list args;
    va_start(args, fmt);
    vsnprintf(reason, sizeof reason, fmt, args);
    va_end(args);
    r->code = fc_error_set(r->err, code, "%s: %s", r->message, reason);
}

/* The next n bytes, or NULL (recording MALFORMED) when the payload ends first. */
static const uint8_t *take(wire_reader *r, size_t n, const char *field)
{
    if (r->code != FC_OK)
        return NULL;
    if (n > wire_remaining(r)) {
        wire_fail(r, FC_ERR_MALFORMED, "payload ends inside %s (%zu bytes needed, %zu left)", field, n,
                  wire_remaining(r));
        return NULL;
    }
    const uint8_t *at = r->p + r->pos;
    r->pos += n;
    return at;
}

static uint64_t get_le(wire_reader *r, size_t bytes, const char *field)
{
    const uint8_t *at = take(r, bytes, field);
    return at ? load_le(at, bytes) : 0;
}

uint16_t wire_get_u16(wire_reader *r, const char *field) { return (uint16_t)get_le(r, 2, field); }
uint32_t wire_get_u32(wire_reader *r, const char *field) { return (uint32_t)get_le(r, 4, field); }
uint64_t wire_get_u64(wire_reader *r, const char *field) { return get_le(r, 8, field); }
float wire_get_f32(wire_reader *r, const char *field) { return bits_float((uint32_t)get_le(r, 4, field)); }

static void get_words(wire_reader *r, void *out, size_t count, const char *field)
{
    if (count > SIZE_MAX / 4) {
        wire_fail(r, FC_ERR_MALFORMED, "%s is too long", field);
        return;
    }
    const uint8_t *at = take(r, count * 4, field);
    if (!at)
        return;
    if (HOST_IS_LITTLE_ENDIAN) {
        memcpy(out, at, count * 4);
        return;
    }
    uint8_t *dst = out;
    for (size_t i = 0; i < count; i++) {
        uint32_t w = (uint32_t)load_le(at + 4 * i, 4);
        memcpy(dst + 4 * i, &w, 4);
    }
}

void wire_words_to_host(uint8_t *words, size_t count)
{
    if (HOST_IS_LITTLE_ENDIAN)
        return;
    for (size_t i = 0; i < count; i++) {
        uint32_t w = (uint32_t)load_le(words + 4 * i, 4);
        memcpy(words + 4 * i, &w, 4);
    }
}

void wire_get_f32_array(wire_reader *r, float *out, size_t count, const char *field) { get_words(r, out, count, field); }
void wire_get_u32_array(wire_reader *r, uint32_t *out, size_t count, const char *field) { get_words(r, out, count, field); }

const uint8_t *wire_get_bytes(wire_reader *r, size_t n, const char *field)
{
    return take(r, n, field);
}

void wire_get_str(wire_reader *r, char *out, size_t capacity, const char *field)
{
    size_t len = wire_get_u16(r, field);
    const uint8_t *text = take(r, len, field);
    if (!text)
        return;
    if (memchr(text, '\0', len)) {
        wire_fail(r, FC_ERR_MALFORMED, "%s contains a NUL byte", field);
        return;
    }
    size_t kept = len < capacity ? len : capacity - 1;
    /* Never keep half of a multi-byte character: back off to its first byte. */
    if (kept < len)
        while (kept > 0 && (text[kept] & UTF8_CONTINUATION_MASK) == UTF8_CONTINUATION_BITS)
            kept--;
    memcpy(out, text, kept);
    out[kept] = '\0';
}

void wire_expect_end(wire_reader *r)
{
    if (r->code == FC_OK && wire_remaining(r) != 0)
        wire_fail(r, FC_ERR_MALFORMED, "%zu unexpected bytes after the last field", wire_remaining(r));
}

fc_code wire_read_empty(const uint8_t *p, size_t n, const char *message, fc_error *err)
{
    wire_reader r = wire_reader_start(p, n, message, err);
    wire_expect_end(&r);
    return r.code;
}
