/* test_service_ingest.c — a producer streaming same-sized frames reuses the
 * daemon's frame blocks instead of allocating new ones: 200 frames over a real
 * socket (FRAME, zstd and quantised FRAME_PACKED, two-chunk CHUNK frames) leave
 * the daemon's count of block allocations (logged when it stops) far below
 * one per frame, every frame is published, and a frame decoded into a recycled
 * block is still validated exactly. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_util.h"

enum {
    PARTICLES = 20000,           /* 240 kB of positions: above the pool's 64 KiB minimum */
    FRAMES_PER_KIND = 50,
    CHUNK_FRAME_BASE = 1000,     /* chunk frame numbers: above the plain frames' 1..150 */
    MAX_BLOCK_ALLOCATIONS = 20   /* measured: 6; without reuse 153 */
};

static const char *const daemon_args[] = {"--log-level", "info", NULL};

/* A frame of the stream: a 200 x 100 sheet moving along z, different every frame. */
static void fill_frame(fc_frame *f, int number)
{
    for (int i = 0; i < PARTICLES; i++) {
        f->positions[3 * i] = 0.01f * (float)(i % 200);
        f->positions[3 * i + 1] = 0.01f * (float)(i / 200);
        f->positions[3 * i + 2] = 0.001f * (float)number + 0.0001f * (float)(i % 7);
    }
}

static bool send_frame(int fd, uint32_t request_id, const fc_frame *f, int kind)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_code code = kind == 0 ? fc_wire_write_frame(&b, request_id, f, &err)
                 : kind == 1 ? fc_wire_write_frame_packed(&b, request_id, f, FC_PACK_ZSTD, 1, &err)
                             : fc_wire_write_frame_packed(&b, request_id, f, FC_PACK_QUANTIZE16, 0, &err);
    bool sent = code == FC_OK && svc_send(fd, &b);
    fc_buf_free(&b);
    return sent;
}

/* The frame as chunks 0 and 1 of frame `number`: the first and second half of its particles. */
static bool send_chunks(int fd, uint32_t request_id, const fc_frame *f, uint64_t number)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    bool sent = true;
    for (uint32_t index = 0; index < 2 && sent; index++) {
        fc_frame half = {.count = PARTICLES / 2, .positions = f->positions + index * 3 * (PARTICLES / 2)};
        fc_chunk_header h = {number, index, 2};
        sent = fc_wire_write_chunk(&b, request_id, &h, &half, 0, 0, &err) == FC_OK && svc_send(fd, &b);
    }
    fc_buf_free(&b);
    return sent;
}

static bool read_reply(int fd, uint16_t type, fc_test_message *reply)
{
    fc_error err;
    if (fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, reply, &err) != FC_OK) {
        fprintf(stderr, "reading a reply: %s\n", err.message);
        return false;
    }
    return reply->header.type == type;
}

static void publish(int fd)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_test_message reply = {0};
    CHECK(fc_wire_write_publish(&b, 1, "ingest", &err) == FC_OK && svc_send(fd, &b));
    CHECK(read_reply(fd, FC_MSG_SESSION_STATE, &reply));
    fc_test_message_free(&reply);
    fc_buf_free(&b);
}

/* Every frame was taken: the session published `frames`, the last numbered last_frame. */
static void check_published(int fd, uint64_t frames, uint64_t last_frame)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_test_message reply = {0};
    CHECK(fc_wire_write_list_sessions(&b, 9, &err) == FC_OK && svc_send(fd, &b));
    fc_session_info *list = NULL;
    uint32_t count = 0;
    if (read_reply(fd, FC_MSG_SESSION_LIST, &reply))
        CHECK_CODE(fc_wire_read_session_list(reply.payload, reply.header.length, &list, &count, &err), FC_OK);
    else
        CHECK_MSG(false, "LIST_SESSIONS answered by type %u", reply.header.type);
    CHECK(count == 1);
    if (count == 1) {
        CHECK_MSG(list[0].frames == frames, "%llu frames published, expected %llu",
                  (unsigned long long)list[0].frames, (unsigned long long)frames);
        CHECK_MSG(list[0].last_frame == last_frame, "last frame %llu, expected %llu",
                  (unsigned long long)list[0].last_frame, (unsigned long long)last_frame);
    }
    free(list);
    fc_test_message_free(&reply);
    fc_buf_free(&b);
}

static void stream(uint16_t port)
{
    fc_welcome welcome;
    int fd = svc_raw_connect(port, FC_CAPS_ALL, 0, &welcome);
    CHECK(fd >= 0);
    if (fd < 0)
        return;
    publish(fd);
    fc_frame f;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&f, PARTICLES, 0, &err), FC_OK);
    uint32_t request_id = 10;
    for (int kind = 0; kind < 3; kind++)
        for (int i = 0; i < FRAMES_PER_KIND; i++) {
            fill_frame(&f, kind * FRAMES_PER_KIND + i);
            CHECK(send_frame(fd, request_id++, &f, kind));
        }
    for (int i = 0; i < FRAMES_PER_KIND; i++) {
        fill_frame(&f, 3 * FRAMES_PER_KIND + i);
        CHECK(send_chunks(fd, request_id++, &f, CHUNK_FRAME_BASE + (uint64_t)i));
    }
    check_published(fd, 4 * FRAMES_PER_KIND, CHUNK_FRAME_BASE + FRAMES_PER_KIND - 1);

    /* A small FRAME after a compressed one arrives in the connection's larger
     * buffer: it is copied out rather than keep that buffer, and still taken. */
    fc_frame small = {.count = 100, .positions = f.positions};
    CHECK(send_frame(fd, request_id++, &f, 1));
    CHECK(send_frame(fd, request_id++, &small, 0));
    check_published(fd, 4 * FRAMES_PER_KIND + 2, CHUNK_FRAME_BASE + FRAMES_PER_KIND + 1);

    /* Into a recycled block: still refused, naming the particle. */
    f.positions[3 * 1234 + 2] = 1.0f / 0.0f;
    CHECK(send_frame(fd, 77, &f, 0));
    fc_error remote;
    CHECK(svc_expect_error(fd, 77, FC_ERR_INVALID_VALUE, &remote));
    CHECK_MSG(strstr(remote.message, "particle 1234 ") != NULL, "%s", remote.message);
    fc_frame_free(&f);
    close(fd);
}

/* The count the daemon logs when it stops, or -1. */
static long logged_allocations(FILE *log)
{
    char line[512];
    long count = -1;
    rewind(log);
    while (fgets(line, sizeof line, log)) {
        const char *at = strstr(line, "frame blocks allocated: ");
        if (at)
            count = strtol(at + strlen("frame blocks allocated: "), NULL, 10);
    }
    return count;
}

int main(void)
{
    /* The daemon inherits stderr: point it at a file for the time of the start. */
    FILE *log = tmpfile();
    CHECK(log != NULL);
    if (!log)
        return test_result();
    int saved_stderr = dup(STDERR_FILENO);
    fflush(stderr);
    dup2(fileno(log), STDERR_FILENO);
    fc_test_daemon d;
    svc_start_daemon(&d, daemon_args);
    dup2(saved_stderr, STDERR_FILENO);
    close(saved_stderr);

    stream(d.port);
    CHECK(svc_stop_daemon(&d));
    long allocations = logged_allocations(log);
    fprintf(stderr, "frame block allocations for %d frames: %ld\n", 4 * FRAMES_PER_KIND, allocations);
    CHECK_MSG(allocations >= 1 && allocations <= MAX_BLOCK_ALLOCATIONS, "%ld block allocations", allocations);
    fclose(log);
    return test_result();
}
