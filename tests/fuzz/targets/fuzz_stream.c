/* fuzz_stream.c — the message stream reader the message targets share. */
#include "fuzz_stream.h"

#include <stdlib.h>
#include <string.h>

#include "fuzz_check.h"

void fuzz_require_same_payload(const fc_buf *encoded, fuzz_payload in)
{
    FUZZ_REQUIRE(!encoded->failed && encoded->len == FC_WIRE_HEADER_SIZE + in.n,
                 "re-encoded %zu bytes for a %zu-byte payload", encoded->len, in.n);
    FUZZ_REQUIRE(in.n == 0 || memcmp(encoded->data + FC_WIRE_HEADER_SIZE, in.p, in.n) == 0,
                 "re-encoded payload differs");
}

void fuzz_require_image_in_payload(const fc_image_reply *image, fuzz_payload in)
{
    FUZZ_REQUIRE(image->size <= in.n && image->data == in.p + (in.n - image->size),
                 "image data is not the payload's tail");
    FUZZ_REQUIRE(image->format >= FC_FORMAT_PNG && image->format <= FC_FORMAT_H264, "format %d", (int)image->format);
    FUZZ_REQUIRE(image->aov >= FC_AOV_COLOR && image->aov <= FC_AOV_NOISE, "aov %d", (int)image->aov);
}

uint32_t fuzz_load_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

uint64_t fuzz_load_u64(const uint8_t *p)
{
    return fuzz_load_u32(p) | (uint64_t)fuzz_load_u32(p + 4) << 32;
}

/* A refused payload is the sender's fault, so its code is one a server sends back. */
static void check_payload_refusal(fc_code code, const fc_error *err)
{
    fuzz_require_reported(code, err);
    FUZZ_REQUIRE(code == FC_ERR_MALFORMED || code == FC_ERR_INVALID_VALUE || code == FC_ERR_LIMIT,
                 "payload refused with code %d: %s", (int)code, err->message);
}

static void decode_copy(uint16_t type, const uint8_t *p, size_t n, fuzz_payload_decoder decode)
{
    uint8_t *copy = malloc(n);
    FUZZ_REQUIRE(copy != NULL || n == 0, "cannot copy a %zu-byte payload", n);
    if (n > 0)
        memcpy(copy, p, n);
    fc_error err = {FC_OK, ""};
    fc_code code = decode(type, (fuzz_payload){copy, n}, &err);
    if (code != FC_OK)
        check_payload_refusal(code, &err);
    free(copy);
}

void fuzz_read_messages(const uint8_t *data, size_t size, fuzz_payload_decoder decode)
{
    while (size >= FC_WIRE_HEADER_SIZE) {
        fc_msg_header header;
        fc_error err = {FC_OK, ""};
        fc_code code = fc_wire_decode_header(data, FUZZ_MAX_PAYLOAD, &header, &err);
        if (code != FC_OK) {
            fuzz_require_reported(code, &err);
            FUZZ_REQUIRE(code == FC_ERR_BAD_MAGIC || code == FC_ERR_TOO_LARGE || code == FC_ERR_MALFORMED,
                         "header refused with code %d", (int)code);
            return; /* the connection would be closed here */
        }
        FUZZ_REQUIRE(header.length <= FUZZ_MAX_PAYLOAD, "accepted length %u", header.length);
        data += FC_WIRE_HEADER_SIZE;
        size -= FC_WIRE_HEADER_SIZE;
        if (header.length > size)
            return; /* the stream ends inside this message */
        decode_copy(header.type, data, header.length, decode);
        data += header.length;
        size -= header.length;
    }
}
