/* fuzz_wire_session.c — libFuzzer target for the session, streaming and packed
 * frame decoders (types 16..24, wire_session.h): the input is a byte stream of
 * messages, read by fuzz_read_messages (fuzz_stream.h); core messages have
 * their own target, fuzz_wire_messages. Packed bodies are decoded with every
 * encoding allowed and at most FUZZ_MAX_PARTICLES particles.
 *
 * Decoded messages are checked against their contract. The messages whose
 * encoding is canonical (PUBLISH, SESSION_STATE, SESSION_END, SESSION_LIST,
 * SUBSCRIBE but for quality 0) must re-encode to the very bytes received; the
 * others (STREAM_IMAGE, packed bodies) must survive the encoder (fuzz_packed.h). */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fc_frame.h"
#include "fuzz_check.h"
#include "fuzz_packed.h"
#include "fuzz_stream.h"
#include "wire_session.h"

#define SUBSCRIBE_QUALITY_OFFSET 4u
#define CHUNK_HEADER_SIZE 16u     /* frame_number, index, count */

/* The re-encoding of a canonical message reproduces its payload; frees *encoded. */
static void require_reencoded_same(fc_code code, fc_buf *encoded, const fc_error *err, fuzz_payload in)
{
    FUZZ_REQUIRE(code == FC_OK, "re-encoding failed: %s", err->message);
    fuzz_require_same_payload(encoded, in);
    fc_buf_free(encoded);
}

static void require_session_name(const char *name)
{
    fuzz_require_terminated(name, FC_SESSION_NAME_MAX + 1);
    size_t len = strlen(name);
    FUZZ_REQUIRE(len >= 1 && len <= FC_SESSION_NAME_MAX, "a %zu-byte session name", len);
}

static fc_code decode_publish(fuzz_payload in, fc_error *err)
{
    char name[FC_SESSION_NAME_MAX + 1];
    fc_code code = fc_wire_read_publish(in.p, in.n, name, err);
    if (code != FC_OK)
        return code;
    require_session_name(name);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    require_reencoded_same(fc_wire_write_publish(&encoded, 0, name, &check), &encoded, &check, in);
    return FC_OK;
}

static fc_code decode_subscribe(fuzz_payload in, fc_error *err)
{
    fc_subscribe m;
    fc_code code = fc_wire_read_subscribe(in.p, in.n, &m, err);
    if (code != FC_OK)
        return code;
    require_session_name(m.name);
    /* The request follows RENDER's rules (fuzz_wire_messages checks those in full). */
    FUZZ_REQUIRE(m.request.quality >= 1 && m.request.quality <= 100, "quality %u", m.request.quality);
    FUZZ_REQUIRE(m.request.aov <= FC_AOV_NOISE, "aov %d", (int)m.request.aov);
    FUZZ_REQUIRE((m.width == 0) == (m.height == 0), "size %ux%u", m.width, m.height);
    FUZZ_REQUIRE(m.request.format != FC_FORMAT_H264 || (m.width % 2 == 0 && m.height % 2 == 0),
                 "H.264 at an odd size %ux%u", m.width, m.height);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    code = fc_wire_write_subscribe(&encoded, 0, &m, &check);
    if (fuzz_load_u32(in.p + SUBSCRIBE_QUALITY_OFFSET) != 0) { /* quality 0 is decoded as the default */
        require_reencoded_same(code, &encoded, &check, in);
        return FC_OK;
    }
    fc_subscribe again;
    FUZZ_REQUIRE(code == FC_OK && fc_wire_read_subscribe(encoded.data + FC_WIRE_HEADER_SIZE,
                                                         encoded.len - FC_WIRE_HEADER_SIZE, &again, &check) == FC_OK,
                 "re-encoded SUBSCRIBE refused: %s", check.message);
    FUZZ_REQUIRE(memcmp(&again.request, &m.request, sizeof m.request) == 0 && again.width == m.width &&
                     again.height == m.height && strcmp(again.name, m.name) == 0,
                 "SUBSCRIBE changed in an encode/decode round trip");
    fc_buf_free(&encoded);
    return FC_OK;
}

static fc_code decode_session_state(fuzz_payload in, fc_error *err)
{
    fc_session_info m;
    fc_code code = fc_wire_read_session_state(in.p, in.n, &m, err);
    if (code != FC_OK)
        return code;
    require_session_name(m.name);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    require_reencoded_same(fc_wire_write_session_state(&encoded, 0, &m, &check), &encoded, &check, in);
    return FC_OK;
}

/* SESSION_END is empty from a client and names the session from the server:
 * exactly one of the two readers accepts a well-formed payload. */
static fc_code decode_session_end(fuzz_payload in, fc_error *err)
{
    fc_error leave_err = {FC_OK, ""};
    fc_code leave = fc_wire_read_session_leave(in.p, in.n, &leave_err);
    FUZZ_REQUIRE((leave == FC_OK) == (in.n == 0), "client SESSION_END of %zu bytes: code %d", in.n, (int)leave);
    if (leave != FC_OK) {
        fuzz_require_reported(leave, &leave_err);
        FUZZ_REQUIRE(leave == FC_ERR_MALFORMED, "client SESSION_END refused with code %d", (int)leave);
    }
    char name[FC_SESSION_NAME_MAX + 1];
    fc_code code = fc_wire_read_session_end(in.p, in.n, name, err);
    if (code != FC_OK)
        return leave == FC_OK ? FC_OK : code;
    require_session_name(name);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    require_reencoded_same(fc_wire_write_session_end(&encoded, 0, name, &check), &encoded, &check, in);
    return FC_OK;
}

static bool stage_measured(float ms)
{
    return ms >= 0.0f;
}

/* IMAGE carries only the stages measured: those must come back bit for bit. */
static bool same_image(const fc_image_reply *a, const fc_image_reply *b)
{
    bool same = a->width == b->width && a->height == b->height && a->format == b->format && a->aov == b->aov &&
                a->size == b->size && (a->size == 0 || memcmp(a->data, b->data, (size_t)a->size) == 0);
    for (int s = 0; s < FC_STAGE_COUNT; s++) {
        bool measured = stage_measured(a->stage_ms[s]);
        same = same && measured == stage_measured(b->stage_ms[s]) &&
               (!measured || memcmp(&a->stage_ms[s], &b->stage_ms[s], sizeof(float)) == 0);
    }
    return same;
}

static fc_code decode_stream_image(fuzz_payload in, fc_error *err)
{
    fc_stream_tag tag;
    fc_image_reply image;
    fc_code code = fc_wire_read_stream_image(in.p, in.n, &tag, &image, err);
    if (code != FC_OK)
        return code;
    fuzz_require_image_in_payload(&image, in);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_stream_image(&encoded, 0, &tag, &image, &check) == FC_OK, "re-encoding failed: %s",
                 check.message);
    fc_stream_tag tag_again;
    fc_image_reply image_again;
    FUZZ_REQUIRE(fc_wire_read_stream_image(encoded.data + FC_WIRE_HEADER_SIZE, encoded.len - FC_WIRE_HEADER_SIZE,
                                           &tag_again, &image_again, &check) == FC_OK,
                 "re-encoded STREAM_IMAGE refused: %s", check.message);
    FUZZ_REQUIRE(memcmp(&tag_again, &tag, sizeof tag) == 0 && same_image(&image_again, &image),
                 "STREAM_IMAGE changed in an encode/decode round trip");
    fc_buf_free(&encoded);
    return FC_OK;
}

static fc_code decode_chunk(fuzz_payload in, fc_error *err)
{
    fc_chunk_header h;
    fc_frame part = {0};
    fc_code code = fc_wire_read_chunk(in.p, in.n, FC_PACK_ALL, FUZZ_MAX_PARTICLES, &h, &part, err);
    if (code != FC_OK)
        return code;
    FUZZ_REQUIRE(in.n >= CHUNK_HEADER_SIZE && h.frame_number == fuzz_load_u64(in.p) &&
                 h.index == fuzz_load_u32(in.p + 8) && h.count == fuzz_load_u32(in.p + 12),
                 "chunk header differs from its bytes");
    fuzz_check_packed_body((fuzz_payload){in.p + CHUNK_HEADER_SIZE, in.n - CHUNK_HEADER_SIZE}, &part);
    fc_frame_free(&part);
    return FC_OK;
}

static fc_code decode_frame_packed(fuzz_payload in, fc_error *err)
{
    fc_frame frame = {0};
    fc_code code = fc_wire_read_frame_packed(in.p, in.n, FC_PACK_ALL, FUZZ_MAX_PARTICLES, &frame, err);
    if (code != FC_OK)
        return code;
    fuzz_check_packed_body(in, &frame);
    fc_frame_free(&frame);
    return FC_OK;
}

static fc_code decode_list_sessions(fuzz_payload in, fc_error *err)
{
    fc_code code = fc_wire_read_list_sessions(in.p, in.n, err);
    FUZZ_REQUIRE((code == FC_OK) == (in.n == 0), "LIST_SESSIONS of %zu bytes: code %d", in.n, (int)code);
    return code;
}

static fc_code decode_session_list(fuzz_payload in, fc_error *err)
{
    fc_session_info *sessions;
    uint32_t count;
    fc_code code = fc_wire_read_session_list(in.p, in.n, &sessions, &count, err);
    if (code != FC_OK) {
        FUZZ_REQUIRE(sessions == NULL && count == 0, "a refused SESSION_LIST left %u sessions", count);
        return code;
    }
    for (uint32_t i = 0; i < count; i++)
        require_session_name(sessions[i].name);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    require_reencoded_same(fc_wire_write_session_list(&encoded, 0, sessions, count, &check), &encoded, &check, in);
    free(sessions);
    return FC_OK;
}

static fc_code decode_payload(uint16_t type, fuzz_payload in, fc_error *err)
{
    switch (type) {
    case FC_MSG_PUBLISH: return decode_publish(in, err);
    case FC_MSG_SUBSCRIBE: return decode_subscribe(in, err);
    case FC_MSG_SESSION_STATE: return decode_session_state(in, err);
    case FC_MSG_SESSION_END: return decode_session_end(in, err);
    case FC_MSG_STREAM_IMAGE: return decode_stream_image(in, err);
    case FC_MSG_CHUNK: return decode_chunk(in, err);
    case FC_MSG_FRAME_PACKED: return decode_frame_packed(in, err);
    case FC_MSG_LIST_SESSIONS: return decode_list_sessions(in, err);
    case FC_MSG_SESSION_LIST: return decode_session_list(in, err);
    }
    return FC_OK; /* not a session message: fuzz_wire_messages decodes the others */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_read_messages(data, size, decode_payload);
    return 0;
}
