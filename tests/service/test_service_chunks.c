/* test_service_chunks.c — multi-rank frames against the real fluidcastd: a
 * frame sent as K chunks over K connections (out of order) renders pixel for
 * pixel like the same frame sent whole; every chunk error comes with its exact
 * code and the request id of the offending chunk; a frame still missing chunks
 * after the timeout is reported INCOMPLETE to every rank that sent one. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_util.h"

enum { RANKS = 3, WIDTH = 61, HEIGHT = 47, TIMEOUT_MS = 500 };

static const char *const daemon_args[] = {"--max-image", "256x256", "--chunk-timeout-ms", "500", NULL};

/* The grid with a density per particle, so attributes travel in the chunks too. */
static fc_frame dense_grid(void)
{
    fc_frame grid = {0}, frame = {0};
    fc_error err;
    CHECK_CODE(svc_grid_frame(0.0f, &grid, &err), FC_OK);
    CHECK_CODE(fc_frame_alloc(&frame, grid.count, FC_ATTR_DENSITY, &err), FC_OK);
    memcpy(frame.positions, grid.positions, 3 * grid.count * sizeof(float));
    for (uint64_t i = 0; i < frame.count; i++)
        frame.density[i] = 1000.0f + (float)i;
    fc_frame_free(&grid);
    return frame;
}

/* Particles [begin, end) of a frame, as a frame of their own (arrays borrowed). */
static fc_frame slice(const fc_frame *f, uint64_t begin, uint64_t end)
{
    return (fc_frame){.count = end - begin, .positions = f->positions + 3 * begin, .density = f->density + begin};
}

static fc_client *viewer(const fc_test_daemon *d, const char *session)
{
    fc_client *c = svc_client(d, session);
    fc_camera cam;
    fc_settings settings;
    fc_error err;
    svc_axis_camera(2.0f, WIDTH, HEIGHT, &cam);
    svc_settings(&settings);
    settings.smoothing = FC_SMOOTHING_CURVATURE;   /* the whole pipeline, not just the depth */
    fc_render_request request = {.format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_COLOR};
    bool ok = c && fc_client_set_camera(c, &cam, &err) == FC_OK && fc_client_set_settings(c, &settings, &err) == FC_OK &&
              fc_client_subscribe(c, session, &request, WIDTH, HEIGHT, NULL, &err) == FC_OK;
    CHECK_MSG(ok, "viewer of %s: %s", session, c ? err.message : "no connection");
    return c;
}

static bool next_image(fc_client *c, fc_stream_image *img)
{
    fc_error err;
    if (fc_client_next_image(c, img, &err) == FC_OK && !img->ended && img->image.data)
        return true;
    fprintf(stderr, "no stream image: %s\n", err.message);
    return false;
}

static void test_chunks_render_like_the_whole_frame(const fc_test_daemon *d)
{
    fc_frame frame = dense_grid();
    fc_client *whole_viewer = viewer(d, "whole");
    fc_client *ranks_viewer = viewer(d, "ranks");
    fc_client *producer = svc_client(d, "whole producer");
    fc_client *ranks[RANKS];
    fc_error err;
    CHECK(producer && fc_client_publish(producer, "whole", NULL, &err) == FC_OK);
    CHECK(fc_client_send_frame(producer, &frame, &err) == FC_OK);
    for (int r = 0; r < RANKS; r++) {
        ranks[r] = svc_client(d, "rank");
        CHECK(ranks[r] && fc_client_publish(ranks[r], "ranks", NULL, &err) == FC_OK);
    }
    /* Uneven slices, sent last rank first: the server must order them by index. */
    const uint64_t bounds[RANKS + 1] = {0, 10, 70, frame.count};
    fc_upload_options zstd = {.encoding = FC_UPLOAD_ZSTD};
    for (int r = RANKS - 1; r >= 0; r--) {
        fc_frame part = slice(&frame, bounds[r], bounds[r + 1]);
        CHECK_CODE(fc_client_send_chunk(ranks[r], 1, (uint32_t)r, RANKS, &part, r == 1 ? &zstd : NULL, NULL, &err),
                   FC_OK);
    }
    fc_stream_image from_whole, from_ranks;
    if (next_image(whole_viewer, &from_whole) && next_image(ranks_viewer, &from_ranks)) {
        CHECK(from_whole.frame_number == 1 && from_ranks.frame_number == 1);
        CHECK(from_whole.image.size == (size_t)WIDTH * HEIGHT * 4);
        CHECK_MSG(from_whole.image.size == from_ranks.image.size &&
                      memcmp(from_whole.image.data, from_ranks.image.data, from_whole.image.size) == 0,
                  "the chunked frame renders differently");
        /* The assembled frame's telemetry: receiving and decoding its chunks, the queues. */
        const float *ms = from_ranks.image.stage_ms;
        CHECK_MSG(ms[FC_STAGE_RECEIVE] >= 0.0f && ms[FC_STAGE_DECODE] >= 0.0f && ms[FC_STAGE_QUEUE] >= 0.0f &&
                      ms[FC_STAGE_ENCODE] >= 0.0f && ms[FC_STAGE_TOTAL] >= ms[FC_STAGE_ENCODE],
                  "receive %g decode %g queue %g encode %g total %g", ms[FC_STAGE_RECEIVE], ms[FC_STAGE_DECODE],
                  ms[FC_STAGE_QUEUE], ms[FC_STAGE_ENCODE], ms[FC_STAGE_TOTAL]);
        fc_stream_image_free(&from_whole);
        fc_stream_image_free(&from_ranks);
    }
    for (int r = 0; r < RANKS; r++)
        fc_client_close(ranks[r]);
    fc_client_close(producer);
    fc_client_close(whole_viewer);
    fc_client_close(ranks_viewer);
    fc_frame_free(&frame);
}

/* Sends one CHUNK of frame `number` holding `particles` grid particles (with
 * densities when dense). */
static bool send_chunk(int fd, uint32_t id, uint64_t number, uint32_t index, uint32_t count, bool dense)
{
    fc_frame frame = dense_grid();
    fc_frame part = slice(&frame, 0, 5);
    if (!dense)
        part.density = NULL;
    fc_chunk_header h = {number, index, count};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    bool ok = fc_wire_write_chunk(&b, id, &h, &part, 0, 0, &err) == FC_OK && svc_send(fd, &b);
    fc_buf_free(&b);
    fc_frame_free(&frame);
    return ok;
}

static int publisher(const fc_test_daemon *d, const char *session)
{
    fc_welcome welcome;
    int fd = svc_raw_connect(d->port, FC_CAP_SESSIONS, 0, &welcome);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_test_message state = {0};
    bool ok = fd >= 0 && fc_wire_write_publish(&b, 1, session, &err) == FC_OK && svc_send(fd, &b) &&
              fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &state, &err) == FC_OK &&
              state.header.type == FC_MSG_SESSION_STATE;
    CHECK_MSG(ok, "PUBLISH %s", session);
    fc_test_message_free(&state);
    fc_buf_free(&b);
    return fd;
}

static void test_chunk_errors(const fc_test_daemon *d)
{
    fc_error remote;
    fc_welcome welcome;
    int outsider = svc_raw_connect(d->port, FC_CAP_SESSIONS, 0, &welcome);
    CHECK(send_chunk(outsider, 2, 1, 0, 2, false) && svc_expect_error(outsider, 2, FC_ERR_BAD_STATE, &remote));
    close(outsider);

    int a = publisher(d, "errors");
    /* Valid chunks are not answered: each error below names its own request. */
    CHECK(send_chunk(a, 10, 1, 0, 2, false));
    CHECK(send_chunk(a, 11, 1, 0, 2, false) && svc_expect_error(a, 11, FC_ERR_DUPLICATE, &remote));
    CHECK(send_chunk(a, 12, 1, 2, 2, false) && svc_expect_error(a, 12, FC_ERR_INVALID_VALUE, &remote));
    CHECK(send_chunk(a, 13, 1, 1, 3, false) && svc_expect_error(a, 13, FC_ERR_INCONSISTENT, &remote));
    CHECK(send_chunk(a, 14, 1, 0, 0, false) && svc_expect_error(a, 14, FC_ERR_INVALID_VALUE, &remote));
    CHECK(send_chunk(a, 15, 1, 1, 2, true) && svc_expect_error(a, 15, FC_ERR_INCONSISTENT, &remote));
    CHECK(send_chunk(a, 16, 1, 1, 2, false));   /* completes frame 1 */
    CHECK(send_chunk(a, 17, 1, 0, 2, false) && svc_expect_error(a, 17, FC_ERR_DUPLICATE, &remote));
    CHECK(send_chunk(a, 19, 0, 0, 2, false) && svc_expect_error(a, 19, FC_ERR_BAD_STATE, &remote));

    /* Frame 2 of three chunks gets two, from two ranks: both hear of it, with their own request ids. */
    int b = publisher(d, "errors");
    double sent = svc_now_ms();
    CHECK(send_chunk(b, 30, 2, 0, 3, false));
    CHECK(send_chunk(a, 18, 2, 1, 3, false));
    CHECK(svc_expect_error(a, 18, FC_ERR_INCOMPLETE, &remote));
    double waited = svc_now_ms() - sent;
    CHECK(svc_expect_error(b, 30, FC_ERR_INCOMPLETE, &remote));
    CHECK_MSG(strstr(remote.message, "2 of its 3 chunks") != NULL, "message \"%s\"", remote.message);
    /* Not before the chunk timeout (its clock starts after `sent`); how much later depends on the machine's load. */
    CHECK_MSG(waited >= TIMEOUT_MS - 50, "INCOMPLETE after %.0f ms, before the chunk timeout", waited);
    close(a);
    close(b);
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, daemon_args);
    test_chunks_render_like_the_whole_frame(&daemon);
    test_chunk_errors(&daemon);
    CHECK(svc_stop_daemon(&daemon));
    return test_result();
}
