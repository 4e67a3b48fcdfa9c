/* test_hardening_chunks.c — multi-rank frames gone wrong, against the real
 * fluidcastd: CHUNK without the capability or without PUBLISH, bad chunk
 * counts and indices, duplicates, disagreeing chunks, quotas, broken packed
 * bodies, frames that time out (INCOMPLETE, also to a second rank and after
 * a rank vanished), and session messages only a server may send.
 *
 * Cases that leave a frame open complete it after the offending chunk, so no
 * INCOMPLETE arrives later in place of the render that checks the connection. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "hardening_harness.h"
#include "test_util.h"
#include "wire_session.h"

#define MAX_PARTICLES 4096u
static const char *const daemon_args[] = {"--max-particles", "4096", "--chunk-timeout-ms", "1000", NULL};

/* ---- raw CHUNK messages ---- */

typedef struct chunk_spec {
    uint64_t frame_number;
    uint32_t index, count;       /* i of K */
    uint64_t particles;
    uint32_t attributes;
} chunk_spec;

/* The FRAME payload layout of `particles` particles on a line, ids counting up. */
static void inner_frame(fc_buf *out, uint64_t particles, uint32_t attributes)
{
    hx_u64(out, particles);
    hx_u32(out, attributes);
    hx_u32(out, 0);
    for (uint64_t i = 0; i < particles; i++) {
        hx_f32(out, 0.05f * (float)i);
        hx_f32(out, 0.0f);
        hx_f32(out, 0.0f);
    }
    for (uint64_t i = 0; (attributes & 1u) && i < particles; i++)
        hx_f32(out, 1000.0f);
    for (uint64_t i = 0; (attributes & 2u) && i < 3 * particles; i++)
        hx_f32(out, 0.0f);
    for (uint64_t i = 0; (attributes & 4u) && i < particles; i++)
        hx_u32(out, (uint32_t)i);
}

static uint64_t inner_size(uint64_t particles, uint32_t attributes)
{
    uint64_t stride = 12 + ((attributes & 1u) ? 4 : 0) + ((attributes & 2u) ? 12 : 0) + ((attributes & 4u) ? 4 : 0);
    return 16 + particles * stride;
}

static void chunk_header(fc_buf *out, const chunk_spec *c)
{
    hx_u64(out, c->frame_number);
    hx_u32(out, c->index);
    hx_u32(out, c->count);
}

/* CHUNK with a plain packed body (encoding 0: raw_size = the inner bytes). */
static void chunk(fc_buf *out, uint32_t request_id, chunk_spec c)
{
    size_t at = hx_begin(out, FC_MSG_CHUNK, request_id);
    chunk_header(out, &c);
    hx_u32(out, 0);
    hx_u32(out, 0);
    hx_u64(out, inner_size(c.particles, c.attributes));
    inner_frame(out, c.particles, c.attributes);
    hx_end(out, at);
}

/* CHUNK whose packed body says `encoding` and raw_size but carries `body`. */
static void chunk_with_body(fc_buf *out, uint32_t encoding, uint64_t raw_size, const void *body, size_t n)
{
    size_t at = hx_begin(out, FC_MSG_CHUNK, HX_BAD_ID);
    chunk_header(out, &(chunk_spec){1, 0, 1, 0, 0});
    hx_u32(out, encoding);
    hx_u32(out, 0);
    hx_u64(out, raw_size);
    hx_bytes(out, body, n);
    hx_end(out, at);
}

/* ---- table cases ---- */

static void one_chunk(fc_buf *out)
{
    chunk(out, HX_BAD_ID, (chunk_spec){1, 0, 1, 10, 0});
}

static void chunk_count_zero(fc_buf *out)
{
    chunk(out, HX_BAD_ID, (chunk_spec){1, 0, 0, 10, 0});
}

static void chunk_index_equals_count(fc_buf *out)
{
    chunk(out, HX_BAD_ID, (chunk_spec){1, 2, 2, 10, 0});
}

static void chunk_count_beyond_max(fc_buf *out)
{
    chunk(out, HX_BAD_ID, (chunk_spec){1, 0, FC_CHUNK_COUNT_MAX + 1, 10, 0});
}

static void duplicate_index(fc_buf *out)
{
    chunk(out, HX_PRELUDE_ID, (chunk_spec){1, 0, 2, 10, 0});
    chunk(out, HX_BAD_ID, (chunk_spec){1, 0, 2, 10, 0});
    chunk(out, HX_PRELUDE_ID + 1, (chunk_spec){1, 1, 2, 10, 0});
}

static void count_disagrees(fc_buf *out)
{
    chunk(out, HX_PRELUDE_ID, (chunk_spec){1, 0, 2, 10, 0});
    chunk(out, HX_BAD_ID, (chunk_spec){1, 1, 3, 10, 0});
    chunk(out, HX_PRELUDE_ID + 1, (chunk_spec){1, 1, 2, 10, 0});
}

static void attributes_disagree(fc_buf *out)
{
    chunk(out, HX_PRELUDE_ID, (chunk_spec){1, 0, 2, 10, 0});
    chunk(out, HX_BAD_ID, (chunk_spec){1, 1, 2, 10, 1});
    chunk(out, HX_PRELUDE_ID + 1, (chunk_spec){1, 1, 2, 10, 0});
}

static void chunk_of_completed_frame(fc_buf *out)
{
    chunk(out, HX_PRELUDE_ID, (chunk_spec){5, 0, 1, 10, 0});
    chunk(out, HX_BAD_ID, (chunk_spec){5, 0, 1, 10, 0});
}

static void chunk_of_older_frame(fc_buf *out)
{
    chunk(out, HX_PRELUDE_ID, (chunk_spec){5, 0, 1, 10, 0});
    chunk(out, HX_BAD_ID, (chunk_spec){4, 0, 1, 10, 0});
}

static void chunks_beyond_quota(fc_buf *out)
{
    chunk(out, HX_PRELUDE_ID, (chunk_spec){1, 0, 2, 3000, 0});
    chunk(out, HX_BAD_ID, (chunk_spec){1, 1, 2, 3000, 0});
    chunk(out, HX_PRELUDE_ID + 1, (chunk_spec){1, 1, 2, 1000, 0});
}

static void one_chunk_beyond_quota(fc_buf *out)
{
    chunk(out, HX_BAD_ID, (chunk_spec){1, 0, 1, MAX_PARTICLES + 1, 0});
}

/* FC_ASSEMBLY_MAX_FRAMES (8) frames open at once; a ninth is refused. */
static void too_many_open_frames(fc_buf *out)
{
    for (uint64_t f = 1; f <= 8; f++)
        chunk(out, HX_PRELUDE_ID, (chunk_spec){f, 0, 2, 4, 0});
    chunk(out, HX_BAD_ID, (chunk_spec){9, 0, 2, 4, 0});
    for (uint64_t f = 1; f <= 8; f++)
        chunk(out, HX_PRELUDE_ID + 1, (chunk_spec){f, 1, 2, 4, 0});
}

static void missing_chunk(fc_buf *out)
{
    chunk(out, HX_BAD_ID, (chunk_spec){1, 0, 2, 10, 0});
}

static void unknown_encoding_bit(fc_buf *out)
{
    chunk_with_body(out, 4, 0, NULL, 0);
}

static void raw_size_disagrees(fc_buf *out)
{
    fc_buf inner;
    fc_buf_init(&inner);
    inner_frame(&inner, 2, 0);
    chunk_with_body(out, 0, inner.len + 1, inner.data, inner.len);
    fc_buf_free(&inner);
}

static void zstd_garbage(fc_buf *out)
{
    static const uint8_t garbage[16] = {0x28, 0xb5, 0x2f, 0xfd, 0xff, 0xff, 0xff, 0xff, 1, 2, 3, 4, 5, 6, 7, 8};
    chunk_with_body(out, FC_PACK_ZSTD, 40, garbage, sizeof garbage);
}

/* A tiny body claiming to expand to a terabyte: refused before any allocation. */
static void zstd_bomb(fc_buf *out)
{
    static const uint8_t body[8] = {0x28, 0xb5, 0x2f, 0xfd, 0, 0, 0, 0};
    chunk_with_body(out, FC_PACK_ZSTD, 1ull << 40, body, sizeof body);
}

static void session_state_from_client(fc_buf *out)
{
    fc_session_info info = {.name = "fake", .producers = 1};
    fc_error err;
    CHECK_CODE(fc_wire_write_session_state(out, HX_BAD_ID, &info, &err), FC_OK);
}

static void stream_image_from_client(fc_buf *out)
{
    static const uint8_t pixel[4] = {1, 2, 3, 4};
    fc_stream_tag tag = {1, 1, 0, 0};
    fc_image_reply image = {.width = 1, .height = 1, .format = FC_FORMAT_RAW, .aov = FC_AOV_COLOR, .data = pixel,
                            .size = 4};
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        image.stage_ms[s] = -1.0f;
    fc_error err;
    CHECK_CODE(fc_wire_write_stream_image(out, HX_BAD_ID, &tag, &image, &err), FC_OK);
}

static void session_list_from_client(fc_buf *out)
{
    fc_error err;
    CHECK_CODE(fc_wire_write_session_list(out, HX_BAD_ID, NULL, 0, &err), FC_OK);
}

static const hx_case cases[] = {
    {"CHUNK without the SESSIONS capability", HX_GREETED, one_chunk, FC_ERR_UNKNOWN_TYPE, HX_STAYS_OPEN, false},
    {"CHUNK before PUBLISH", HX_GREETED_ALL, one_chunk, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"CHUNK: K = 0", HX_PUBLISHING, chunk_count_zero, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"CHUNK: index = K", HX_PUBLISHING, chunk_index_equals_count, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"CHUNK: K beyond 4096", HX_PUBLISHING, chunk_count_beyond_max, FC_ERR_INVALID_VALUE, HX_STAYS_OPEN, false},
    {"CHUNK: index arrives twice", HX_PUBLISHING, duplicate_index, FC_ERR_DUPLICATE, HX_STAYS_OPEN, false},
    {"CHUNK: K disagrees", HX_PUBLISHING, count_disagrees, FC_ERR_INCONSISTENT, HX_STAYS_OPEN, false},
    {"CHUNK: attributes disagree", HX_PUBLISHING, attributes_disagree, FC_ERR_INCONSISTENT, HX_STAYS_OPEN, false},
    {"CHUNK: frame complete already", HX_PUBLISHING, chunk_of_completed_frame, FC_ERR_DUPLICATE, HX_STAYS_OPEN,
     false},
    {"CHUNK: frame older than a complete one", HX_PUBLISHING, chunk_of_older_frame, FC_ERR_BAD_STATE,
     HX_STAYS_OPEN, false},
    {"CHUNK: chunks together beyond the quota", HX_PUBLISHING, chunks_beyond_quota, FC_ERR_LIMIT, HX_STAYS_OPEN,
     false},
    {"CHUNK: one chunk beyond the quota", HX_PUBLISHING, one_chunk_beyond_quota, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"CHUNK: a ninth open frame", HX_PUBLISHING, too_many_open_frames, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"CHUNK: missing chunk times out", HX_PUBLISHING, missing_chunk, FC_ERR_INCOMPLETE, HX_STAYS_OPEN, false},
    {"CHUNK: unknown encoding bit", HX_PUBLISHING, unknown_encoding_bit, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"CHUNK: raw_size disagrees with the body", HX_PUBLISHING, raw_size_disagrees, FC_ERR_MALFORMED, HX_STAYS_OPEN,
     false},
    {"CHUNK: zstd body is garbage", HX_PUBLISHING, zstd_garbage, FC_ERR_MALFORMED, HX_STAYS_OPEN, false},
    {"CHUNK: zstd body claims a terabyte", HX_PUBLISHING, zstd_bomb, FC_ERR_LIMIT, HX_STAYS_OPEN, false},
    {"SESSION_STATE from a client", HX_GREETED_ALL, session_state_from_client, FC_ERR_BAD_STATE, HX_STAYS_OPEN,
     false},
    {"STREAM_IMAGE from a client", HX_GREETED_ALL, stream_image_from_client, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
    {"SESSION_LIST from a client", HX_GREETED_ALL, session_list_from_client, FC_ERR_BAD_STATE, HX_STAYS_OPEN, false},
};

/* ---- several ranks ---- */

static void send_chunk(int fd, uint32_t request_id, chunk_spec c)
{
    fc_buf out;
    fc_buf_init(&out);
    chunk(&out, request_id, c);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
}

/* Returns once the daemon has handled everything sent on fd so far: a
 * connection's messages are handled in order, but connections race each other. */
static void sync_with_daemon(int fd, uint32_t request_id)
{
    fc_buf out;
    fc_buf_init(&out);
    hx_header(&out, FC_MSG_LIST_SESSIONS, 0, request_id, 0);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_reply_type(fd, request_id, FC_MSG_SESSION_LIST);
}

static int rank(hx_env *env, const char *session)
{
    int fd = hx_connect_greeted(env, FC_CAPS_ALL);
    if (fd >= 0)
        hx_publish(fd, session);
    return fd;
}

/* Rank 1 sends the chunk rank 0 sent already. */
static void test_duplicate_across_ranks(hx_env *env)
{
    printf("case: two ranks send the same chunk\n");
    int a = rank(env, "ranks-duplicate"), b = rank(env, "ranks-duplicate");
    if (a < 0 || b < 0)
        return;
    send_chunk(a, 10, (chunk_spec){1, 0, 2, 10, 0});
    sync_with_daemon(a, 12);
    send_chunk(b, HX_BAD_ID, (chunk_spec){1, 0, 2, 10, 0});
    hx_expect_error(b, HX_BAD_ID, FC_ERR_DUPLICATE);
    send_chunk(b, 11, (chunk_spec){1, 1, 2, 10, 0});
    hx_expect_witness_served(env);
    hx_expect_renders(a, 100);
    hx_expect_renders(b, 100);
    close(a);
    close(b);
}

/* Every rank that contributed to a frame that timed out hears of it, with its own request id. */
static void test_incomplete_reaches_every_rank(hx_env *env)
{
    printf("case: an incomplete frame is reported to every rank\n");
    int a = rank(env, "ranks-incomplete"), b = rank(env, "ranks-incomplete");
    if (a < 0 || b < 0)
        return;
    send_chunk(a, 20, (chunk_spec){1, 0, 3, 10, 0});
    send_chunk(b, 21, (chunk_spec){1, 2, 3, 10, 0});
    hx_expect_error(a, 20, FC_ERR_INCOMPLETE);
    hx_expect_error(b, 21, FC_ERR_INCOMPLETE);
    hx_expect_witness_served(env);
    hx_expect_renders(a, 100);
    hx_expect_renders(b, 100);
    close(a);
    close(b);
}

/* A rank leaves with its chunk in an open frame: the frame times out and
 * only the rank still there is told (nothing is sent to the one that left). */
static void test_rank_leaves_mid_frame(hx_env *env)
{
    printf("case: a rank disconnects with its chunk in an open frame\n");
    int a = rank(env, "ranks-leaving"), b = rank(env, "ranks-leaving");
    if (a < 0 || b < 0)
        return;
    send_chunk(a, 30, (chunk_spec){1, 0, 2, 10, 0});
    sync_with_daemon(a, 32);
    send_chunk(b, 31, (chunk_spec){2, 0, 2, 10, 0});
    hx_expect_witness_served(env);
    close(a);
    /* Frame 1 opened first, so it has expired (reported to nobody) by now. */
    hx_expect_error(b, 31, FC_ERR_INCOMPLETE);
    hx_expect_witness_served(env);
    hx_expect_renders(b, 100);
    close(b);
}

/* Compressed bodies need the ZSTD capability even on a publishing connection. */
static void test_zstd_not_negotiated(hx_env *env)
{
    printf("case: CHUNK: zstd body without the ZSTD capability\n");
    int fd = hx_connect_greeted(env, FC_CAP_SESSIONS);
    if (fd < 0)
        return;
    hx_publish(fd, "zstd-not-negotiated");
    fc_buf out;
    fc_buf_init(&out);
    zstd_garbage(&out);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_error(fd, HX_BAD_ID, FC_ERR_BAD_STATE);
    hx_expect_witness_served(env);
    hx_expect_renders(fd, 100);
    close(fd);
}

int main(void)
{
    hx_env env;
    if (!hx_env_start(&env, daemon_args))
        return hx_exit_status(test_result());
    hx_run_cases(&env, cases, sizeof cases / sizeof cases[0]);
    test_duplicate_across_ranks(&env);
    test_incomplete_reaches_every_rank(&env);
    test_rank_leaves_mid_frame(&env);
    test_zstd_not_negotiated(&env);
    hx_env_stop(&env);
    return hx_exit_status(test_result());
}
