/* test_hardening_memory.c — the per-connection memory limit
 * (--max-session-memory, PROTOCOL.md 6.4) against the real fluidcastd, set
 * to LIMIT_BYTES. A frame counts 16 bytes per particle of positions only (12
 * of positions, 4 of the noise amplitude kept for rendering), so the sizes
 * below are known exactly:
 *
 *   - a FRAME that alone exceeds the limit gets ERROR LIMIT naming the limit,
 *     and the frame sent before still renders; one that fits replaces it;
 *   - an IMAGE reply beyond the limit is answered with ERROR LIMIT instead;
 *   - a BACKGROUND that decodes beyond it gets ERROR LIMIT, the one before stays;
 *   - a CHUNK whose frame's assembly would exceed it gets ERROR LIMIT (the
 *     other rank's chunk then times out INCOMPLETE), and the producers' next
 *     frame reaches the session's viewer.
 * Meanwhile the witness, a connection of its own, keeps being served. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "hardening_harness.h"
#include "image_encoder.h"
#include "test_scene.h"
#include "test_util.h"
#include "wire_scene.h"
#include "wire_session.h"

#define LIMIT_BYTES 100000u
#define BYTES_PER_PARTICLE 16u
#define LIMIT_NAME "max_session_memory"

static const char *const daemon_args[] = {"--max-session-memory", "100000", "--chunk-timeout-ms", "1000", NULL};

/* `count` particles 0.01 apart on a line, positions only. */
static bool line_frame(uint64_t count, fc_frame *frame)
{
    fc_error err;
    if (fc_frame_alloc(frame, count, 0, &err) != FC_OK) {
        CHECK_MSG(0, "%s", err.message);
        return false;
    }
    for (uint64_t i = 0; i < count; i++) {
        frame->positions[3 * i] = 0.01f * (float)i;
        frame->positions[3 * i + 1] = 0.0f;
        frame->positions[3 * i + 2] = 0.0f;
    }
    return true;
}

static void send_line_frame(int fd, uint32_t request_id, uint64_t count)
{
    fc_frame frame = {0};
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    if (line_frame(count, &frame))
        CHECK_CODE(fc_wire_write_frame(&out, request_id, &frame, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    fc_frame_free(&frame);
}

static void test_frame_beyond_limit(hx_env *env)
{
    printf("case: a FRAME beyond the limit\n");
    int fd = hx_connect_greeted(env, 0);
    hx_expect_renders(fd, 10);
    uint64_t too_many = LIMIT_BYTES / BYTES_PER_PARTICLE + 1;
    send_line_frame(fd, 20, too_many);
    hx_expect_error_mentioning(fd, 20, FC_ERR_LIMIT, LIMIT_NAME);
    hx_expect_witness_served(env);
    /* Still the cube, with the camera of the sequence. */
    hx_send_render(fd, 21, FC_FORMAT_RAW, FC_AOV_DEPTH);
    hx_expect_cube_image(fd, 21);
    /* A frame that fits once the cube it replaces is given up: accepted and rendered. */
    send_line_frame(fd, 22, (LIMIT_BYTES - 8192) / BYTES_PER_PARTICLE);
    hx_send_render(fd, 23, FC_FORMAT_RAW, FC_AOV_DEPTH);
    hx_expect_reply_type(fd, 23, FC_MSG_IMAGE);
    close(fd);
}

static void test_reply_beyond_limit(hx_env *env)
{
    printf("case: an IMAGE beyond the limit\n");
    int fd = hx_connect_greeted(env, 0);
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    /* 200 x 200 float depths: 160000 bytes of RAW image. */
    fc_render_request request = {FC_FORMAT_RAW, 0, FC_AOV_DEPTH};
    CHECK_CODE(fc_test_write_render_sequence(&out, 10, 200, 200, &request, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_error_mentioning(fd, 12, FC_ERR_LIMIT, LIMIT_NAME);
    hx_expect_renders(fd, 20);
    close(fd);
}

/* A side x side RGBA PNG of 8-bit samples: decoded, 4 bytes per pixel. */
static bool big_png(uint32_t side, fc_buf *out)
{
    size_t bytes = (size_t)side * side * 4;
    uint8_t *pixels = malloc(bytes);
    if (!pixels)
        return false;
    for (size_t i = 0; i < bytes; i++)
        pixels[i] = (uint8_t)(i * 7);
    fc_image image = {side, side, 4, FC_PIXEL_U8, pixels, bytes};
    fc_error err;
    bool ok = fc_encode_image(&image, FC_FORMAT_PNG, 0, out, &err) == FC_OK;
    CHECK_MSG(ok, "%s", err.message);
    free(pixels);
    return ok;
}

static void test_background_beyond_limit(hx_env *env)
{
    printf("case: a BACKGROUND beyond the limit\n");
    int fd = hx_connect_greeted(env, 0);
    fc_buf png, out;
    fc_error err;
    fc_buf_init(&png);
    fc_buf_init(&out);
    hx_send_magenta_background(fd, 10);
    if (big_png(200, &png)) {
        fc_encoded_image file = {png.data, png.len};
        CHECK_CODE(fc_wire_write_background(&out, 11, &file, &err), FC_OK);
        hx_send_buf(fd, &out);
        hx_expect_error_mentioning(fd, 11, FC_ERR_LIMIT, LIMIT_NAME);
    }
    hx_write_render_sequence(&out, 20);
    hx_send_buf(fd, &out);
    hx_expect_cube_image(fd, 22);
    hx_send_render(fd, 23, FC_FORMAT_RAW, FC_AOV_COLOR);
    hx_expect_magenta_image(fd, 23, NULL);
    fc_buf_free(&png);
    fc_buf_free(&out);
    close(fd);
}

/* Chunk `index` of 2 of `frame_number`: particles [first, first + count) of `whole`. */
static void send_chunk(int fd, uint32_t request_id, uint64_t frame_number, uint32_t index, const fc_frame *whole,
                       uint64_t first, uint64_t count)
{
    fc_frame part = {.count = count, .positions = whole->positions + 3 * first};
    fc_chunk_header header = {frame_number, index, 2};
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_wire_write_chunk(&out, request_id, &header, &part, 0, 0, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
}

/* Returns once the daemon has handled everything fd sent before: it answers in order. */
static void sync_with(int fd, uint32_t request_id)
{
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_wire_write_list_sessions(&out, request_id, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_reply_type(fd, request_id, FC_MSG_SESSION_LIST);
}

static int subscribe(hx_env *env, const char *session, uint32_t request_id)
{
    int fd = hx_connect_greeted(env, FC_CAP_SESSIONS);
    fc_subscribe sub = {.request = {FC_FORMAT_RAW, 0, FC_AOV_DEPTH}, .width = HX_IMAGE_SIDE, .height = HX_IMAGE_SIDE};
    snprintf(sub.name, sizeof sub.name, "%s", session);
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_wire_write_subscribe(&out, request_id, &sub, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_reply_type(fd, request_id, FC_MSG_SESSION_STATE);
    return fd;
}

static void expect_stream_frame(int fd, uint32_t subscribe_id, uint64_t frame_number)
{
    fc_test_message m;
    fc_error err;
    if (fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &m, &err) != FC_OK) {
        CHECK_MSG(0, "expected a STREAM_IMAGE: %s", err.message);
        return;
    }
    fc_stream_tag tag = {0};
    fc_image_reply image;
    CHECK_MSG(m.header.type == FC_MSG_STREAM_IMAGE && m.header.request_id == subscribe_id,
              "got type %u for request %u", m.header.type, m.header.request_id);
    if (m.header.type == FC_MSG_STREAM_IMAGE)
        CHECK_CODE(fc_wire_read_stream_image(m.payload, m.header.length, &tag, &image, &err), FC_OK);
    CHECK_MSG(tag.frame_number == frame_number, "stream image of frame %llu, expected %llu",
              (unsigned long long)tag.frame_number, (unsigned long long)frame_number);
    fc_test_message_free(&m);
}

/* An H.264 viewer's encoder counts (24 bytes per pixel + 4 MiB): beyond a 100 kB limit at any size. */
static void test_h264_viewer_beyond_limit(hx_env *env)
{
    printf("case: an H.264 viewer whose encoder goes beyond the limit\n");
    int fd = hx_connect_greeted(env, FC_CAP_SESSIONS);
    fc_subscribe sub = {.request = {FC_FORMAT_H264, 0, FC_AOV_COLOR}, .width = HX_IMAGE_SIDE, .height = HX_IMAGE_SIDE};
    snprintf(sub.name, sizeof sub.name, "%s", "memory-h264");
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    CHECK_CODE(fc_wire_write_subscribe(&out, 31, &sub, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_error_mentioning(fd, 31, FC_ERR_LIMIT, LIMIT_NAME);
    hx_expect_witness_served(env);
    /* Refused, the connection is in no session: a RAW subscription on it goes through. */
    sub.request = (fc_render_request){FC_FORMAT_RAW, 0, FC_AOV_DEPTH};
    fc_buf_init(&out);
    CHECK_CODE(fc_wire_write_subscribe(&out, 32, &sub, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
    hx_expect_reply_type(fd, 32, FC_MSG_SESSION_STATE);
    close(fd);
}

static void test_chunks_beyond_limit(hx_env *env)
{
    printf("case: chunks whose assembly goes beyond the limit\n");
    const char *session = "memory-chunks";
    int viewer = subscribe(env, session, 5);
    int rank0 = hx_connect_greeted(env, FC_CAPS_ALL);
    int rank1 = hx_connect_greeted(env, FC_CAPS_ALL);
    hx_publish(rank0, session);
    hx_publish(rank1, session);
    /* Each chunk alone fits; both together do not. */
    uint64_t half = LIMIT_BYTES / BYTES_PER_PARTICLE * 2 / 3;
    fc_frame line = {0};
    fc_frame cube = {0};
    fc_error err;
    if (line_frame(2 * half, &line) && fc_test_cube_frame(&cube, &err) == FC_OK) {
        send_chunk(rank0, 10, 1, 0, &line, 0, half);
        sync_with(rank0, 20);
        send_chunk(rank1, 11, 1, 1, &line, half, half);
        hx_expect_error_mentioning(rank1, 11, FC_ERR_LIMIT, LIMIT_NAME);
        hx_expect_witness_served(env);
        hx_expect_error(rank0, 10, FC_ERR_INCOMPLETE);
        /* The next frame, small, goes through to the viewer. */
        send_chunk(rank0, 12, 2, 0, &cube, 0, cube.count / 2);
        send_chunk(rank1, 13, 2, 1, &cube, cube.count / 2, cube.count - cube.count / 2);
        expect_stream_frame(viewer, 5, 2);
    }
    fc_frame_free(&line);
    fc_frame_free(&cube);
    close(rank0);
    close(rank1);
    close(viewer);
}

int main(void)
{
    hx_env env;
    if (!hx_env_start(&env, daemon_args))
        return hx_exit_status(1);
    test_frame_beyond_limit(&env);
    test_h264_viewer_beyond_limit(&env);
    test_reply_beyond_limit(&env);
    test_background_beyond_limit(&env);
    test_chunks_beyond_limit(&env);
    hx_env_stop(&env);
    return hx_exit_status(0);
}
