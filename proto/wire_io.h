/* wire_io.h — internal to the proto library: little-endian primitives the
 * message codecs are written with. Not installed, not part of the contract. */
#ifndef FC_WIRE_IO_H
#define FC_WIRE_IO_H

#include "wire.h"

/* 1 where the host stores words as the wire does (least significant byte first). */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define WIRE_HOST_IS_LITTLE_ENDIAN 1
#else
#define WIRE_HOST_IS_LITTLE_ENDIAN 0
#endif

/* Writes the low `bytes` bytes of v, least significant first. */
void wire_store_le(uint8_t *out, uint64_t v, size_t bytes);

/* ---- Writing: appends to an fc_buf; no-ops once the buffer has failed. ---- */
void wire_put_bytes(fc_buf *b, const void *bytes, size_t n);
void wire_put_u16(fc_buf *b, uint16_t v);
void wire_put_u32(fc_buf *b, uint32_t v);
void wire_put_u64(fc_buf *b, uint64_t v);
void wire_put_f32(fc_buf *b, float v);
void wire_put_f32_array(fc_buf *b, const float *v, size_t count);
void wire_put_u32_array(fc_buf *b, const uint32_t *v, size_t count);
/* u16 length + bytes of the NUL-terminated text in a char array of `capacity` bytes. */
void wire_put_str(fc_buf *b, const char *text, size_t capacity);
/* Bytes a wire_put_str of this text takes. */
size_t wire_str_size(const char *text, size_t capacity);

/* Starts a message of `length` payload bytes; returns where it begins in b. */
size_t wire_begin_message(fc_buf *b, fc_msg_type type, uint32_t request_id, uint32_t length);
/* The same for a message of which only the header and the first part_bytes of
 * the payload go into b (the rest is sent from where it lies). */
size_t wire_begin_message_part(fc_buf *b, fc_msg_type type, uint32_t request_id, uint32_t length,
                               size_t part_bytes);
/* FC_OK, or FC_ERR_NOMEM after taking the incomplete message back out of b. */
fc_code wire_end_message(fc_buf *b, size_t start, fc_error *err);
/* FC_ERR_TOO_LARGE unless a payload of fixed + count * unit bytes (fixed below
 * 4 GiB, unit >= 1) fits the u32 length field; never overflows computing it. */
fc_code wire_check_length(uint64_t fixed, uint64_t count, uint64_t unit, const char *message, fc_error *err);

/* A message with no payload (GOODBYE, LIST_SESSIONS, a viewer's SESSION_END). */
fc_code wire_write_empty(fc_buf *b, fc_msg_type type, uint32_t request_id, fc_error *err);

/* ---- Reading: a cursor over one payload. The first failure sticks: later
 * reads return zeros and leave the error as it was, so a decoder reads every
 * field and checks `code` once. ---- */
typedef struct wire_reader {
    const uint8_t *p;
    size_t n;
    size_t pos;
    const char *message;   /* e.g. "HELLO", for error messages */
    fc_error *err;
    fc_code code;          /* FC_OK until a read fails */
} wire_reader;

wire_reader wire_reader_start(const uint8_t *p, size_t n, const char *message, fc_error *err);
size_t wire_remaining(const wire_reader *r);
uint16_t wire_get_u16(wire_reader *r, const char *field);
uint32_t wire_get_u32(wire_reader *r, const char *field);
uint64_t wire_get_u64(wire_reader *r, const char *field);
float wire_get_f32(wire_reader *r, const char *field);
void wire_get_f32_array(wire_reader *r, float *out, size_t count, const char *field);
void wire_get_u32_array(wire_reader *r, uint32_t *out, size_t count, const char *field);
/* Copies a string into out[capacity], cut at a UTF-8 character boundary when
 * too long, always NUL-terminated; an embedded NUL is MALFORMED. */
void wire_get_str(wire_reader *r, char *out, size_t capacity, const char *field);
/* Turns `count` little-endian 32-bit words into host order in place (nothing to do on little-endian hosts). */
void wire_words_to_host(uint8_t *words, size_t count);
/* Returns a pointer to the next n bytes (inside the payload) and skips them. */
const uint8_t *wire_get_bytes(wire_reader *r, size_t n, const char *field);
/* MALFORMED when bytes are left over. */
void wire_expect_end(wire_reader *r);
/* Decodes a message with no payload: MALFORMED unless the payload is empty. */
fc_code wire_read_empty(const uint8_t *p, size_t n, const char *message, fc_error *err);
/* Records a failure found by the decoder itself (unless one is recorded already). */
void wire_fail(wire_reader *r, fc_code code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
