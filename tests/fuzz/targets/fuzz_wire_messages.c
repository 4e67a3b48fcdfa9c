/* fuzz_wire_messages.c — libFuzzer target for the decoders of the core
 * messages (types 1..9) and the scene images (BACKGROUND 10, ENVIRONMENT 11):
 * the input is a byte stream as a peer would send it, a sequence of messages,
 * read by fuzz_read_messages (fuzz_stream.h). The session messages (16..24)
 * have a target of their own, fuzz_wire_session.
 *
 * Decoded messages are checked against their contract, and the messages whose
 * encoding is canonical (CAMERA, FRAME, BACKGROUND, ENVIRONMENT) must re-encode
 * to the very bytes received. */
#include <stdbool.h>
#include <stdint.h>

#include "fc_frame.h"
#include "fuzz_check.h"
#include "fuzz_stream.h"
#include "wire.h"
#include "wire_scene.h"

static fc_code decode_hello(fuzz_payload in, fc_error *err)
{
    fc_hello m;
    fc_code code = fc_wire_read_hello(in.p, in.n, &m, err);
    if (code == FC_OK)
        fuzz_require_terminated(m.client_name, sizeof m.client_name);
    return code;
}

static fc_code decode_welcome(fuzz_payload in, fc_error *err)
{
    fc_welcome m;
    fc_code code = fc_wire_read_welcome(in.p, in.n, &m, err);
    if (code == FC_OK) {
        fuzz_require_terminated(m.server_version, sizeof m.server_version);
        fuzz_require_terminated(m.renderer, sizeof m.renderer);
    }
    return code;
}

static fc_code decode_frame(fuzz_payload in, fc_error *err)
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
    fuzz_require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    fc_frame_free(&m);
    return FC_OK;
}

static fc_code decode_camera(fuzz_payload in, fc_error *err)
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
    fuzz_require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    return FC_OK;
}

static fc_code decode_settings(fuzz_payload in, fc_error *err)
{
    fc_settings m;
    fc_settings_default(&m);
    fc_code code = fc_wire_read_settings(in.p, in.n, &m, err);
    fc_error check = {FC_OK, ""};
    if (code == FC_OK)
        FUZZ_REQUIRE(fc_settings_validate(&m, &check) == FC_OK, "decoded settings invalid: %s", check.message);
    return code;
}

static fc_code decode_render(fuzz_payload in, fc_error *err)
{
    fc_render_request m;
    fc_code code = fc_wire_read_render(in.p, in.n, &m, err);
    if (code == FC_OK) {
        FUZZ_REQUIRE(m.format >= FC_FORMAT_PNG && m.format <= FC_FORMAT_H264, "format %d", (int)m.format);
        FUZZ_REQUIRE(m.quality >= 1 && m.quality <= 100, "quality %u", m.quality);
        FUZZ_REQUIRE(m.aov >= FC_AOV_COLOR && m.aov <= FC_AOV_NOISE, "aov %d", (int)m.aov);
        /* PNG, JPEG and H.264 hold 8-bit colour only. */
        FUZZ_REQUIRE(m.aov == FC_AOV_COLOR || m.format == FC_FORMAT_EXR || m.format == FC_FORMAT_RAW,
                     "aov %d accepted in format %d", (int)m.aov, (int)m.format);
    }
    return code;
}

static fc_code decode_image(fuzz_payload in, fc_error *err)
{
    fc_image_reply m;
    fc_code code = fc_wire_read_image(in.p, in.n, &m, err);
    if (code == FC_OK)
        fuzz_require_image_in_payload(&m, in);
    return code;
}

static fc_code decode_error(fuzz_payload in, fc_error *err)
{
    fc_error m;
    fc_code code = fc_wire_read_error(in.p, in.n, &m, err);
    if (code == FC_OK) {
        FUZZ_REQUIRE(m.code >= 1 && m.code <= 99, "ERROR carried local code %d", (int)m.code);
        fuzz_require_terminated(m.message, sizeof m.message);
    }
    return code;
}

static fc_code decode_goodbye(fuzz_payload in, fc_error *err)
{
    fc_code code = fc_wire_read_goodbye(in.p, in.n, err);
    if (code == FC_OK)
        FUZZ_REQUIRE(in.n == 0, "GOODBYE accepted %zu payload bytes", in.n);
    return code;
}

static fc_code decode_background(fuzz_payload in, fc_error *err)
{
    fc_encoded_image m;
    fc_code code = fc_wire_read_background(in.p, in.n, &m, err);
    FUZZ_REQUIRE(code == FC_OK, "BACKGROUND frames any payload, yet refused %zu bytes", in.n);
    FUZZ_REQUIRE(m.size == in.n && m.data == (in.n > 0 ? in.p : NULL), "the file is not the whole payload");
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_background(&encoded, 0, &m, &check) == FC_OK, "re-encoding failed: %s",
                 check.message);
    fuzz_require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    return FC_OK;
}

/* Accepted faces are non-empty and lie back to back in the payload, each after its u64 length. */
static void require_faces_in_payload(const fc_encoded_image *faces, fuzz_payload in)
{
    size_t offset = 0;
    for (int i = 0; i < FC_CUBE_FACES; i++) {
        offset += 8;
        FUZZ_REQUIRE(faces[i].size > 0, "face %s is empty", fc_cube_face_name(i));
        FUZZ_REQUIRE(faces[i].data == in.p + offset && faces[i].size <= in.n - offset,
                     "face %s is not where its length says", fc_cube_face_name(i));
        offset += (size_t)faces[i].size;
    }
    FUZZ_REQUIRE(offset == in.n, "six faces take %zu of %zu payload bytes", offset, in.n);
}

static fc_code decode_environment(fuzz_payload in, fc_error *err)
{
    fc_encoded_image faces[FC_CUBE_FACES];
    bool has_faces = true;
    fc_code code = fc_wire_read_environment(in.p, in.n, faces, &has_faces, err);
    if (code != FC_OK)
        return code;
    FUZZ_REQUIRE(has_faces == (in.n > 0), "%zu payload bytes but has_faces %d", in.n, (int)has_faces);
    if (has_faces)
        require_faces_in_payload(faces, in);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_environment(&encoded, 0, has_faces ? faces : NULL, &check) == FC_OK,
                 "re-encoding failed: %s", check.message);
    fuzz_require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    return FC_OK;
}

/* The extensions this target knows: the scene images. */
static fc_code decode_extension(uint16_t type, fuzz_payload in, fc_error *err)
{
    switch (type) {
    case FC_MSG_BACKGROUND: return decode_background(in, err);
    case FC_MSG_ENVIRONMENT: return decode_environment(in, err);
    }
    return FC_OK; /* no decoder here: the server answers UNKNOWN_TYPE (or fuzz_wire_session decodes it) */
}

static fc_code decode_payload(uint16_t type, fuzz_payload in, fc_error *err)
{
    switch (type) {
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
    return decode_extension(type, in, err);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_read_messages(data, size, decode_payload);
    return 0;
}
