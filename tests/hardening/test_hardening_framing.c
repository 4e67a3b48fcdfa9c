/* test_hardening_framing.c — hostile framing, handshakes, message types, states
 * and payload layouts against the real fluidcastd (PROTOCOL.md sections 2, 3,
 * 4, 7.3 and 8). The daemon allows any particle count, so a FRAME's count x
 * stride overflow is reached (a smaller limit would answer LIMIT first). */
#include <string.h>

#include "hardening_harness.h"
#include "test_util.h"

#define MAX_MESSAGE 65536u

static const char *const daemon_args[] = {"--max-particles", "18446744073709551615", "--max-message", "65536",
                                          "--max-image", "64x64", NULL};

/* ---- framing ---- */

static void http_request(fc_buf *out)
{
    static const char request[] = "GET / HTTP/1.1\r\nHost: fluidcast\r\n\r\n";
    hx_bytes(out, request, sizeof request - 1);
}

static void wrong_magic(fc_buf *out)
{
    hx_bytes(out, "FCSX", 4);
    hx_u16(out, FC_MSG_CAMERA);
    hx_u16(out, 0);
    hx_u32(out, HX_BAD_ID);
    hx_u32(out, 0);
}

static void length_beyond_limit(fc_buf *out)
{
    hx_header(out, FC_MSG_FRAME, 0, HX_BAD_ID, MAX_MESSAGE + 1);
}

static void length_max_u32(fc_buf *out)
{
    hx_header(out, FC_MSG_HELLO, 0, HX_BAD_ID, UINT32_MAX);
}

static void header_cut_short(fc_buf *out)
{
    hx_header(out, FC_MSG_HELLO, 0, HX_BAD_ID, 30);
    out->len -= 6;
}

/* A CAMERA announcing its 48 bytes but delivering 20. */
static void payload_cut_short(fc_buf *out)
{
    hx_header(out, FC_MSG_CAMERA, 0, HX_BAD_ID, 48);
    for (int i = 0; i < 5; i++)
        hx_f32(out, 1.0f);
}

static void camera_payload(fc_buf *out)
{
    static const float vectors[9] = {0, 0, 3, 0, 0, 0, 0, 1, 0};
    for (int i = 0; i < 9; i++)
        hx_f32(out, vectors[i]);
    hx_f32(out, 40.0f);
    hx_u32(out, HX_IMAGE_SIDE);
    hx_u32(out, HX_IMAGE_SIDE);
}

static void nonzero_flags(fc_buf *out)
{
    hx_header(out, FC_MSG_CAMERA, 0x8000, HX_BAD_ID, 48);
    camera_payload(out);
}

/* ---- handshake ---- */

static void hello_versions_above(fc_buf *out)
{
    hx_hello(out, HX_BAD_ID, 2, 5, 0);
}

static void hello_versions_inverted(fc_buf *out)
{
    hx_hello(out, HX_BAD_ID, 1, 0, 0);
}

static void hello_version_zero(fc_buf *out)
{
    hx_hello(out, HX_BAD_ID, 0, 0, 0);
}

/* Every version, capability bits nobody defined, fields of a later version after the name. */
static void hello_from_the_future(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_HELLO, HX_BAD_ID);
    hx_u32(out, 0);
    hx_u32(out, UINT32_MAX);
    hx_u32(out, 0xfffffff8u);
    hx_str(out, "client 9.0");
    hx_u64(out, 0x0123456789abcdefull);
    hx_end(out, at);
}

static void hello_too_short(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_HELLO, HX_BAD_ID);
    hx_u32(out, 1);
    hx_u32(out, 1);
    hx_u16(out, 0);
    hx_end(out, at);
}

static void hello_name_past_payload(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_HELLO, HX_BAD_ID);
    hx_u32(out, 1);
    hx_u32(out, 1);
    hx_u32(out, 0);
    hx_u16(out, 100);
    hx_bytes(out, "abc", 3);
    hx_end(out, at);
}

static void hello_name_with_nul(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_HELLO, HX_BAD_ID);
    hx_u32(out, 1);
    hx_u32(out, 1);
    hx_u32(out, 0);
    hx_u16(out, 5);
    hx_bytes(out, "ab\0cd", 5);
    hx_end(out, at);
}

static void hello_with_flags(fc_buf *out)
{
    size_t at = out->len;
    hx_hello(out, HX_BAD_ID, 1, 1, 0);
    if (!out->failed)
        out->data[at + 6] = 1;   /* flags, low byte */
}

/* ---- types and states ---- */

static void unknown_type_with_payload(fc_buf *out)
{
    hx_header(out, 77, 0, HX_BAD_ID, 8);
    hx_u64(out, 0x4653435446534354ull);   /* "FCSTFCST": must be skipped, not parsed as a header */
}

static void reserved_core_type(fc_buf *out)
{
    hx_header(out, 14, 0, HX_BAD_ID, 0);
}

static void largest_type(fc_buf *out)
{
    hx_header(out, 0xffff, 0, HX_BAD_ID, 4);
    hx_u32(out, 0);
}

static void type_zero(fc_buf *out)
{
    hx_header(out, 0, 0, HX_BAD_ID, 0);
}

/* LIST_SESSIONS exists, but only for connections that negotiated SESSIONS. */
static void extension_not_negotiated(fc_buf *out)
{
    hx_header(out, 23, 0, HX_BAD_ID, 0);
}

static void camera_before_hello(fc_buf *out)
{
    hx_header(out, FC_MSG_CAMERA, 0, HX_BAD_ID, 48);
    camera_payload(out);
}

static void render_before_hello(fc_buf *out)
{
    hx_header(out, FC_MSG_RENDER, 0, HX_BAD_ID, 12);
    hx_u32(out, FC_FORMAT_PNG);
    hx_u32(out, 0);
    hx_u32(out, FC_AOV_COLOR);
}

static void second_hello(fc_buf *out)
{
    hx_hello(out, HX_BAD_ID, 1, 1, 0);
}

static void welcome_from_client(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_WELCOME, HX_BAD_ID);
    hx_u32(out, 1);
    hx_u32(out, 0);
    hx_u64(out, 1000);
    hx_u32(out, 64);
    hx_u32(out, 64);
    hx_u32(out, 65536);
    hx_str(out, "fake");
    hx_str(out, "fake");
    hx_end(out, at);
}

static void image_from_client(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_IMAGE, HX_BAD_ID);
    hx_u32(out, 1);
    hx_u32(out, 1);
    hx_u32(out, FC_FORMAT_RAW);
    hx_u32(out, FC_AOV_COLOR);
    hx_u32(out, 0);
    hx_u64(out, 4);
    hx_u32(out, 0xffffffffu);
    hx_end(out, at);
}

static void error_from_client(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_ERROR, HX_BAD_ID);
    hx_u32(out, FC_ERR_INTERNAL);
    hx_str(out, "the client has a bad day");
    hx_end(out, at);
}

static void goodbye_with_payload(fc_buf *out)
{
    hx_header(out, FC_MSG_GOODBYE, 0, HX_BAD_ID, 4);
    hx_u32(out, 0);
}

static void goodbye(fc_buf *out)
{
    hx_header(out, FC_MSG_GOODBYE, 0, HX_BAD_ID, 0);
}

/* ---- FRAME layouts (7.3) ---- */

/* A FRAME header and fixed part whose arrays follow as `extra` zero bytes. */
static void frame_fixed(fc_buf *out, uint64_t count, uint32_t attributes, uint32_t reserved, size_t extra)
{
    size_t at = hx_begin(out, FC_MSG_FRAME, HX_BAD_ID);
    hx_u64(out, count);
    hx_u32(out, attributes);
    hx_u32(out, reserved);
    for (size_t i = 0; i < extra; i++)
        hx_bytes(out, "", 1);
    hx_end(out, at);
}

/* One particle at the origin. */
static void frame_before_hello(fc_buf *out)
{
    frame_fixed(out, 1, 0, 0, 12);
}

/* (2^59 + 1) x 32 = 2^64 + 32 and (2^62 + 1) x 12 = 3 x 2^64 + 12: a decoder
 * that multiplies without checking sees exactly the bytes that follow. */
static void count_times_stride_overflows(fc_buf *out)
{
    frame_fixed(out, (1ull << 59) + 1, 7, 0, 32);
}

static void count_times_12_overflows(fc_buf *out)
{
    frame_fixed(out, (1ull << 62) + 1, 0, 0, 12);
}

static void count_beyond_payload(fc_buf *out)
{
    frame_fixed(out, 1ull << 40, 0, 0, 12);
}

static void frame_shorter_than_fixed_part(fc_buf *out)
{
    size_t at = hx_begin(out, FC_MSG_FRAME, HX_BAD_ID);
    hx_u64(out, 1);
    hx_u16(out, 0);
    hx_end(out, at);
}

static void frame_unknown_attribute(fc_buf *out)
{
    frame_fixed(out, 1, 8, 0, 12);
}

static void frame_reserved_set(fc_buf *out)
{
    frame_fixed(out, 1, 0, 1, 12);
}

static void frame_one_byte_long(fc_buf *out)
{
    frame_fixed(out, 1, 0, 0, 13);
}

static void camera_47_bytes(fc_buf *out)
{
    hx_header(out, FC_MSG_CAMERA, 0, HX_BAD_ID, 47);
    camera_payload(out);
    out->len -= 1;
}

static void render_13_bytes(fc_buf *out)
{
    hx_header(out, FC_MSG_RENDER, 0, HX_BAD_ID, 13);
    hx_u32(out, FC_FORMAT_RAW);
    hx_u32(out, 0);
    hx_u32(out, FC_AOV_DEPTH);
    hx_bytes(out, "", 1);
}

static const hx_case cases[] = {
    {"wrong magic: HTTP request", HX_RAW, http_request, FC_ERR_BAD_MAGIC, HX_CLOSES, false},
    {"wrong magic after HELLO", HX_GREETED, wrong_magic, FC_ERR_BAD_MAGIC, HX_CLOSES, false},
    {"HELLO: versions 2..5 only", HX_RAW, hello_versions_above, FC_ERR_VERSION, HX_CLOSES, false},
    {"HELLO: version_min > version_max", HX_RAW, hello_versions_inverted, FC_ERR_VERSION, HX_CLOSES, false},
    {"HELLO: version 0", HX_RAW, hello_version_zero, FC_ERR_VERSION, HX_CLOSES, false},
    {"HELLO: any version, unknown capabilities, later fields", HX_RAW, hello_from_the_future, FC_OK, HX_STAYS_OPEN,
     false},
    {"HELLO: shorter than its fields", HX_RAW, hello_too_short, FC_ERR_MALFORMED, HX_CLOSES, false},
    {"HELLO: name runs past the payload", HX_RAW, hello_name_past_payload, FC_ERR_MALFORMED, HX_CLOSES, false},
    {"HELLO: name with a NUL byte", HX_RAW, hello_name_with_nul, FC_ERR_MALFORMED, HX_CLOSES, false},
    {"HELLO: non-zero flags", HX_RAW, hello_with_flags, FC_ERR_MALFORMED, HX_CLOSES, false},
    {"length beyond the message limit", HX_GREETED, length_beyond_limit, FC_ERR_TOO_LARGE, HX_CLOSES, false},
    {"length 2^32-1 before HELLO", HX_RAW, length_max_u32, FC_ERR_TOO_LARGE, HX_CLOSES, false},
    {"header truncated, then EOF", HX_RAW, header_cut_short, FC_OK, HX_CLOSES, true},
    {"payload truncated, then EOF", HX_GREETED, payload_cut_short, FC_OK, HX_CLOSES, true},
    {"non-zero header flags", HX_GREETED, nonzero_flags, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"unknown type before HELLO", HX_RAW, unknown_type_with_payload, FC_ERR_UNKNOWN_TYPE, HX_CLOSES, false},
    {"unknown type: payload skipped", HX_GREETED, unknown_type_with_payload, FC_ERR_UNKNOWN_TYPE, HX_STAYS_OPEN,
     false},
    {"type 14, reserved", HX_GREETED, reserved_core_type, FC_ERR_UNKNOWN_TYPE, HX_STAYS_OPEN, false},
    {"type 65535", HX_GREETED, largest_type, FC_ERR_UNKNOWN_TYPE, HX_STAYS_OPEN, false},
    {"type 0", HX_GREETED, type_zero, FC_ERR_UNKNOWN_TYPE, HX_STAYS_OPEN, false},
    {"extension type not negotiated", HX_GREETED, extension_not_negotiated, FC_ERR_UNKNOWN_TYPE, HX_STAYS_OPEN,
     false},
    {"FRAME before HELLO", HX_RAW, frame_before_hello, FC_ERR_BAD_STATE, HX_CLOSES, false},
    {"CAMERA before HELLO", HX_RAW, camera_before_hello, FC_ERR_BAD_STATE, HX_CLOSES, false},
    {"RENDER before HELLO", HX_RAW, render_before_hello, FC_ERR_BAD_STATE, HX_CLOSES, false},
    {"second HELLO", HX_GREETED, second_hello, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"WELCOME from a client", HX_GREETED, welcome_from_client, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"IMAGE from a client", HX_GREETED, image_from_client, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"ERROR from a client", HX_GREETED, error_from_client, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"GOODBYE with payload", HX_GREETED, goodbye_with_payload, FC_ERR_MALFORMED, HX_CLOSES, false},
    {"GOODBYE with payload before HELLO", HX_RAW, goodbye_with_payload, FC_ERR_MALFORMED, HX_CLOSES, false},
    {"orderly GOODBYE", HX_GREETED, goodbye, FC_OK, HX_CLOSES, false},
    {"FRAME: count x 32 overflows 64 bits", HX_GREETED, count_times_stride_overflows, FC_ERR_MALFORMED,
     HX_STAYS_OPEN, false},
    {"FRAME: count x 12 overflows 64 bits", HX_GREETED, count_times_12_overflows, FC_ERR_MALFORMED, HX_STAYS_OPEN,
     false},
    {"FRAME: 2^40 particles in 12 bytes", HX_GREETED, count_beyond_payload, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"FRAME: shorter than its fixed part", HX_GREETED, frame_shorter_than_fixed_part, FC_ERR_MALFORMED,
     HX_STAYS_OPEN, false},
    {"FRAME: unknown attribute bit", HX_GREETED, frame_unknown_attribute, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"FRAME: reserved field set", HX_GREETED, frame_reserved_set, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"FRAME: one byte too long", HX_GREETED, frame_one_byte_long, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"CAMERA: 47 bytes", HX_GREETED, camera_47_bytes, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"RENDER: 13 bytes", HX_GREETED, render_13_bytes, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
};

int main(void)
{
    hx_env env;
    if (!hx_env_start(&env, daemon_args))
        return hx_exit_status(test_result());
    hx_run_cases(&env, cases, sizeof cases / sizeof cases[0]);
    hx_env_stop(&env);
    return hx_exit_status(test_result());
}
