/* fuzz_stream.h — what the message targets share: reading a byte stream of
 * messages as a receiver does, and comparing a re-encoded message with the
 * payload it came from. */
#ifndef FC_FUZZ_STREAM_H
#define FC_FUZZ_STREAM_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "wire.h"

#define FUZZ_MAX_PAYLOAD (1u << 20)   /* small, so TOO_LARGE is reachable */
#define FUZZ_MAX_PARTICLES 4096u      /* small, so LIMIT is reachable */

/* One payload, exactly as long as its header says. */
typedef struct fuzz_payload {
    const uint8_t *p;
    size_t n;
} fuzz_payload;

/* Decodes one payload of the given message type and checks what it decoded;
 * returns the decoder's code (FC_OK for types the target does not decode). */
typedef fc_code (*fuzz_payload_decoder)(uint16_t type, fuzz_payload in, fc_error *err);

/* Splits data into messages with fc_wire_decode_header and hands each payload,
 * in a heap buffer of exactly its size (so AddressSanitizer sees any read past
 * it), to decode. Checks that every refusal is reported and carries a code a
 * server sends back for a bad payload. */
void fuzz_read_messages(const uint8_t *data, size_t size, fuzz_payload_decoder decode);

/* A message just encoded into an otherwise empty buffer has exactly `in` as its payload. */
void fuzz_require_same_payload(const fc_buf *encoded, fuzz_payload in);

/* A decoded IMAGE (also STREAM_IMAGE's) names a known format and aov, and its
 * data is the tail of the payload `in`. */
void fuzz_require_image_in_payload(const fc_image_reply *image, fuzz_payload in);

/* Little-endian integers at p, for the checks that look at a payload's raw fields. */
uint32_t fuzz_load_u32(const uint8_t *p);
uint64_t fuzz_load_u64(const uint8_t *p);

#endif
