/* fuzz_wire_messages.c — libFuzzer target for the protocol decoder: the input is
 * a byte stream as a peer would send it, a sequence of messages. Each header goes
 * through fc_wire_decode_header and each payload through the fc_wire_read_* of
 * its type, exactly as long as the header says, in a buffer of its own so that
 * AddressSanitizer sees any read past the payload.
 *
 * Decoded messages are checked against their contract, and CAMERA and FRAME,
 * whose encoding is canonical, must re-encode to the very bytes received. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fc_frame.h"
#include "fuzz_check.h"
#include "wire.h"

#define FUZZ_MAX_PAYLOAD (1u << 20)   /* small, so TOO_LARGE is reachable */
#define FUZZ_MAX_PARTICLES 4096u      /* small, so LIMIT is reachable */

typedef struct payload {
    const uint8_t *p;
    size_t n;
} payload;

static void require_same_payload(const fc_buf *encoded, payload in)
{
    FUZZ_REQUIRE(!encoded->failed && encoded->len == FC_WIRE_HEADER_SIZE + in.n,
                 "re-encoded %zu bytes for a %zu-byte payload", encoded->len, in.n);
    FUZZ_REQUIRE(memcmp(encoded->data + FC_WIRE_HEADER_SIZE, in.p, in.n) == 0, "re-encoded payload differs");
}

static fc_code decode_hello(payload in, fc_error *err)
{
    fc_hello m;
    fc_code code = fc_wire_read_hello(in.p, in.n, &m, err);
    if (code == FC_OK)
        fuzz_require_terminated(m.client_name, sizeof m.client_name);
    return code;
}

static fc_code decode_welcome(payload in, fc_error *err)
{
    fc_welcome m;
    fc_code code = fc_wire_read_welcome(in.p, in.n, &m, err);
    if (code == FC_OK) {
        fuzz_require_terminated(m.server_version, sizeof m.server_version);
        fuzz_require_terminated(m.renderer, sizeof m.renderer);
    }
    return code;
}

static fc_code decode_frame(payload in, fc_error *err)
{
    fc_frame m;
    fc_code code = fc_wire_read_frame(in.p, in.n, FUZZ_MAX_PARTICLES, &m, err);
    if (code != FC_OK)
        return code;
    fc_error check = {FC_OK, ""};
    FUZZ_REQUIRE(m.count >= 1 && m.count <= FUZZ_MAX_PARTICLES, "%llu particles", (unsigned long long)m.count);
    FUZZ_REQUIRE(fc_frame_validate(&m, &check) == FC_OK, "decoded frame is invalid: %s", check.message);
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_frame(&encoded, 0, &m, &check) == FC_OK, "re-encoding failed: %s", check.message);
    require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    fc_frame_free(&m);
    return FC_OK;
}

static fc_code decode_camera(payload in, fc_error *err)
{
    fc_camera m;
    fc_code code = fc_wire_read_camera(in.p, in.n, &m, err);
    if (code != FC_OK)
        return code;
    fc_error check = {FC_OK, ""};
    FUZZ_REQUIRE(fc_camera_validate(&m, &check) == FC_OK, "decoded camera is invalid: %s", check.message);
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_camera(&encoded, 0, &m, &check) == FC_OK, "re-encoding failed: %s", check.message);
    require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    return FC_OK;
}

static fc_code decode_settings(payload in, fc_error *err)
{
    fc_settings m;
    fc_settings_default(&m);
    fc_code code = fc_wire_read_settings(in.p, in.n, &m, err);
    fc_error check = {FC_OK, ""};
    if (code == FC_OK)
        FUZZ_REQUIRE(fc_settings_validate(&m, &check) == FC_OK, "decoded settings invalid: %s", check.message);
    return code;
}

static fc_code decode_render(payload in, fc_error *err)
{
    fc_render_request m;
    fc_code code = fc_wire_read_render(in.p, in.n, &m, err);
    if (code == FC_OK) {
        FUZZ_REQUIRE(m.format >= FC_FORMAT_PNG && m.format <= FC_FORMAT_RAW, "format %d", (int)m.format);
        FUZZ_REQUIRE(m.quality >= 1 && m.quality <= 100, "quality %u", m.quality);
        FUZZ_REQUIRE(m.aov >= FC_AOV_COLOR && m.aov <= FC_AOV_THICKNESS, "aov %d", (int)m.aov);
    }
    return code;
}

static fc_code decode_image(payload in, fc_error *err)
{
    fc_image_reply m;
    fc_code code = fc_wire_read_image(in.p, in.n, &m, err);
    if (code == FC_OK) {
        /* The image data is the tail of the payload. */
        FUZZ_REQUIRE(m.size <= in.n && m.data == in.p + (in.n - m.size), "image data is not the payload's tail");
    }
    return code;
}

static fc_code decode_error(payload in, fc_error *err)
{
    fc_error m;
    fc_code code = fc_wire_read_error(in.p, in.n, &m, err);
    if (code == FC_OK) {
        FUZZ_REQUIRE(m.code >= 1 && m.code <= 99, "ERROR carried local code %d", (int)m.code);
        fuzz_require_terminated(m.message, sizeof m.message);
    }
    return code;
}

static fc_code decode_goodbye(payload in, fc_error *err)
{
    fc_code code = fc_wire_read_goodbye(in.p, in.n, err);
    if (code == FC_OK)
        FUZZ_REQUIRE(in.n == 0, "GOODBYE accepted %zu payload bytes", in.n);
    return code;
}

static fc_code decode_payload(uint16_t type, payload in, fc_error *err)
{
    switch ((fc_msg_type)type) {
    case FC_MSG_HELLO: return decode_hello(in, err);
    case FC_MSG_WELCOME: return decode_welcome(in, err);
    case FC_MSG_FRAME: return decode_frame(in, err);
    case FC_MSG_CAMERA: return decode_camera(in, err);
    case FC_MSG_SETTINGS: return decode_settings(in, err);
    case FC_MSG_RENDER: return decode_render(in, err);
    case FC_MSG_IMAGE: return decode_image(in, err);
    case FC_MSG_ERROR: return decode_error(in, err);
    case FC_MSG_GOODBYE: return decode_goodbye(in, err);
    }
    return FC_OK; /* unknown types have no decoder: the server answers UNKNOWN_TYPE */
}

/* A refused payload is the sender's fault, so its code is one a server sends back. */
static void check_payload_refusal(fc_code code, const fc_error *err)
{
    fuzz_require_reported(code, err);
    FUZZ_REQUIRE(code == FC_ERR_MALFORMED || code == FC_ERR_INVALID_VALUE || code == FC_ERR_LIMIT,
                 "payload refused with code %d: %s", (int)code, err->message);
}

/* Decodes one payload from a heap copy of exactly its size. */
static void decode_copy(uint16_t type, const uint8_t *p, size_t n)
{
    uint8_t *copy = malloc(n);
    FUZZ_REQUIRE(copy != NULL || n == 0, "cannot copy a %zu-byte payload", n);
    if (n > 0)
        memcpy(copy, p, n);
    fc_error err = {FC_OK, ""};
    fc_code code = decode_payload(type, (payload){copy, n}, &err);
    if (code != FC_OK)
        check_payload_refusal(code, &err);
    free(copy);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    while (size >= FC_WIRE_HEADER_SIZE) {
        fc_msg_header header;
        fc_error err = {FC_OK, ""};
        fc_code code = fc_wire_decode_header(data, FUZZ_MAX_PAYLOAD, &header, &err);
        if (code != FC_OK) {
            fuzz_require_reported(code, &err);
            FUZZ_REQUIRE(code == FC_ERR_BAD_MAGIC || code == FC_ERR_TOO_LARGE || code == FC_ERR_MALFORMED,
                         "header refused with code %d", (int)code);
            return 0; /* the connection would be closed here */
        }
        FUZZ_REQUIRE(header.length <= FUZZ_MAX_PAYLOAD, "accepted length %u", header.length);
        data += FC_WIRE_HEADER_SIZE;
        size -= FC_WIRE_HEADER_SIZE;
        if (header.length > size)
            return 0; /* the stream ends inside this message */
        decode_copy(header.type, data, header.length);
        data += header.length;
        size -= header.length;
    }
    return 0;
}
