/* test_service_sessions.c — the rest of the service against the real
 * fluidcastd: a version mismatch refused with a clear error; the Unix-domain
 * socket; capabilities gating the session messages; roles and their BAD_STATE
 * errors; the session list and its limit; a viewer's own camera re-rendering
 * the current frame, the lossless refresh after JPEG images, RENDER on a
 * viewer, per-image telemetry; leaving, and a producer's disconnect ending the
 * session (after which the name starts a new one); a viewer leaving a session
 * that ended while its leave was on the way is out, not in error. What a
 * viewer can do in an ended session: test_service_session_end.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "support/image_decode.h"
#include "test_util.h"

enum { SIZE = 41, REFRESH_MS = 300 };

static fc_client *publisher(const fc_test_daemon *d, const char *session)
{
    fc_client *c = svc_client(d, "producer");
    fc_error err;
    CHECK_MSG(c && fc_client_publish(c, session, NULL, &err) == FC_OK, "publish %s: %s", session,
              c ? err.message : "no connection");
    return c;
}

static bool push_frame(fc_client *c, float dz)
{
    fc_frame f = {0};
    fc_error err;
    bool ok = svc_grid_frame(dz, &f, &err) == FC_OK && fc_client_send_frame(c, &f, &err) == FC_OK;
    fc_frame_free(&f);
    return ok;
}

static void test_version_mismatch(const fc_test_daemon *d)
{
    int fd;
    fc_error err, remote;
    CHECK_CODE(fc_test_connect(d->port, &fd, &err), FC_OK);
    fc_hello hello = {2, 3, FC_CAPS_ALL, "from the future", ""};
    fc_buf b;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_hello(&b, 1, &hello, &err), FC_OK);
    CHECK(svc_send(fd, &b));
    CHECK(svc_expect_error(fd, 1, FC_ERR_VERSION, &remote));
    CHECK_MSG(strstr(remote.message, "2..3") && strstr(remote.message, "only 1"), "message \"%s\"", remote.message);
    CHECK_MSG(fc_test_expect_closed(fd, FC_TEST_IO_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    fc_buf_free(&b);
    close(fd);
}

static void test_unix_socket(const char *path)
{
    char address[160];
    snprintf(address, sizeof address, "unix:%s", path);
    fc_client *c = NULL;
    fc_error err;
    CHECK_MSG(fc_client_connect(address, NULL, &c, &err) == FC_OK, "%s: %s", address, err.message);
    if (!c)
        return;
    fc_frame f = {0};
    fc_camera cam;
    fc_settings settings;
    svc_axis_camera(3.0f, SIZE, SIZE, &cam);
    svc_settings(&settings);
    fc_render_request request = {.format = FC_FORMAT_RAW, .aov = FC_AOV_DEPTH};
    fc_image_result image = {0};
    CHECK_CODE(svc_grid_frame(0.1f, &f, &err), FC_OK);
    CHECK(fc_client_send_frame(c, &f, &err) == FC_OK && fc_client_set_camera(c, &cam, &err) == FC_OK &&
          fc_client_set_settings(c, &settings, &err) == FC_OK &&
          fc_client_render(c, &request, &image, &err) == FC_OK);
    CHECK_NEAR(svc_raw_centre(&image), svc_axis_depth(3.0f, 0.1f), 0.01);
    fc_image_result_free(&image);
    fc_frame_free(&f);
    fc_client_close(c);
}

static void test_sessions_need_the_capability(const fc_test_daemon *d)
{
    fc_welcome welcome;
    fc_error err, remote;
    int fd = svc_raw_connect(d->port, 0, 0, &welcome);
    fc_buf b;
    fc_buf_init(&b);
    CHECK(fc_wire_write_publish(&b, 3, "nope", &err) == FC_OK && svc_send(fd, &b));
    CHECK(svc_expect_error(fd, 3, FC_ERR_UNKNOWN_TYPE, &remote));
    CHECK(fc_wire_write_list_sessions(&b, 4, &err) == FC_OK && svc_send(fd, &b));
    CHECK(svc_expect_error(fd, 4, FC_ERR_UNKNOWN_TYPE, &remote));
    fc_buf_free(&b);
    close(fd);
}

/* Waits until the daemon has noticed closed connections and dropped their sessions. */
static bool wait_for_no_sessions(const fc_test_daemon *d)
{
    fc_client *c = svc_client(d, "lister");
    uint32_t count = 1;
    for (int tries = 0; c && count > 0 && tries < 200; tries++) {
        fc_session_status *list = NULL;
        fc_error err;
        if (fc_client_list_sessions(c, &list, &count, &err) != FC_OK)
            break;
        fc_session_list_free(list);
        if (count > 0)
            svc_sleep_ms(20);
    }
    fc_client_close(c);
    return count == 0;
}

static void test_roles(const fc_test_daemon *d)
{
    fc_client *p = publisher(d, "roles");
    fc_client *v = svc_client(d, "viewer");
    fc_client *none = svc_client(d, "bystander");
    fc_render_request request = {.format = FC_FORMAT_PNG};
    fc_error err;
    CHECK_CODE(fc_client_publish(p, "other", NULL, &err), FC_ERR_BAD_STATE);
    CHECK_CODE(fc_client_subscribe(p, "roles", &request, SIZE, SIZE, NULL, &err), FC_ERR_BAD_STATE);
    CHECK_CODE(fc_client_subscribe(v, "roles", &request, SIZE, SIZE, NULL, &err), FC_OK);
    CHECK_CODE(fc_client_subscribe(v, "roles", &request, 0, 7, NULL, &err), FC_ERR_INVALID_VALUE);
    CHECK_CODE(fc_client_leave_session(none, &err), FC_ERR_BAD_STATE);
    CHECK_CODE(fc_client_subscribe(none, "big", &request, 4000, 4000, NULL, &err), FC_ERR_LIMIT);
    /* A viewer's frame is refused; the next waiting call reports it. */
    CHECK(push_frame(v, 0.0f));
    CHECK_CODE(fc_client_leave_session(v, &err), FC_ERR_BAD_STATE);
    CHECK_MSG(strstr(err.message, "does not send frames") != NULL, "\"%s\"", err.message);
    fc_client_close(p);
    fc_client_close(v);
    fc_client_close(none);
    CHECK(wait_for_no_sessions(d));
}

static void test_list_and_limit(const fc_test_daemon *d)
{
    fc_client *alpha = publisher(d, "alpha");
    CHECK(push_frame(alpha, 0.0f) && push_frame(alpha, 0.1f));
    fc_client *beta = svc_client(d, "beta viewer");
    fc_render_request request = {.format = FC_FORMAT_PNG};
    fc_error err;
    fc_session_status status;
    CHECK_CODE(fc_client_subscribe(beta, "beta", &request, SIZE, SIZE, &status, &err), FC_OK);
    CHECK(strcmp(status.name, "beta") == 0 && status.producers == 0 && status.viewers == 1 && status.frames == 0);
    fc_session_status *list = NULL;
    uint32_t count = 0;
    CHECK_CODE(fc_client_list_sessions(alpha, &list, &count, &err), FC_OK);
    CHECK_MSG(count == 2, "%u sessions", count);
    if (count == 2) {
        CHECK(strcmp(list[0].name, "alpha") == 0 && list[0].producers == 1 && list[0].viewers == 0 &&
              list[0].frames == 2 && list[0].last_frame == 2);
        CHECK(strcmp(list[1].name, "beta") == 0 && list[1].producers == 0 && list[1].viewers == 1);
    }
    fc_session_list_free(list);
    /* --max-sessions 3: one more fits, the fourth does not. */
    fc_client *third = publisher(d, "third");
    fc_client *fourth = svc_client(d, "fourth");
    CHECK_CODE(fc_client_publish(fourth, "fourth", NULL, &err), FC_ERR_LIMIT);
    fc_client_close(third);
    fc_client_close(fourth);
    fc_client_close(alpha);
    fc_client_close(beta);
    CHECK(wait_for_no_sessions(d));
}

/* The next stream image that is not a refresh (refreshes may come at any quiet moment). */
static bool next_non_refresh(fc_client *c, fc_stream_image *img)
{
    fc_error err;
    for (;;) {
        if (fc_client_next_image(c, img, &err) != FC_OK) {
            fprintf(stderr, "next image: %s\n", err.message);
            return false;
        }
        if (!img->refresh)
            return true;
        fc_stream_image_free(img);
    }
}

/* The refresh is due REFRESH_MS after the lossy image was started, which was
 * after `pushed_ms`, when the client sent what triggered it. */
static void check_refresh(fc_client *v, uint64_t frame, double pushed_ms)
{
    fc_stream_image img;
    fc_error err;
    CHECK_CODE(fc_client_next_image(v, &img, &err), FC_OK);
    double waited = svc_now_ms() - pushed_ms;
    CHECK_MSG(img.refresh && img.frame_number == frame && img.missed == 0, "refresh %d, frame %llu", img.refresh,
              (unsigned long long)img.frame_number);
    CHECK_MSG(waited >= REFRESH_MS - 5, "refresh after %.0f ms", waited);
    fc_decoded_image png;
    CHECK(img.image.format == FC_FORMAT_PNG &&
          fc_decode_image(img.image.data, img.image.size, "png", 0, &png, &err) == FC_OK);
    if (png.pixels) {
        CHECK(png.width == SIZE && png.height == SIZE);
        fc_decoded_image_free(&png);
    }
    fc_stream_image_free(&img);
}

static void test_viewer_views_and_refresh(const fc_test_daemon *d)
{
    fc_client *v = svc_client(d, "viewer");
    fc_camera cam;
    fc_settings settings;
    svc_axis_camera(3.0f, SIZE, SIZE, &cam);
    svc_settings(&settings);
    fc_render_request jpeg = {.format = FC_FORMAT_JPEG, .quality = 80};
    fc_error err;
    CHECK(fc_client_set_camera(v, &cam, &err) == FC_OK && fc_client_set_settings(v, &settings, &err) == FC_OK &&
          fc_client_subscribe(v, "gamma", &jpeg, SIZE, SIZE, NULL, &err) == FC_OK);
    fc_client *p = publisher(d, "gamma");
    double pushed = svc_now_ms();
    CHECK(push_frame(p, 0.0f));

    fc_stream_image img;
    CHECK(next_non_refresh(v, &img));
    CHECK(img.frame_number == 1 && img.sequence == 1 && img.missed == 0 && !img.view_change);
    CHECK(img.image.format == FC_FORMAT_JPEG && img.image.size > 3 && memcmp(img.image.data, "\xff\xd8\xff", 3) == 0);
    const float *ms = img.image.stage_ms;
    for (int s = FC_STAGE_DEPTH; s < FC_STAGE_COUNT; s++)
        CHECK_MSG(s == FC_STAGE_SMOOTHING || ms[s] >= 0.0f, "stage %d not measured", s);
    CHECK(ms[FC_STAGE_TOTAL] >= ms[FC_STAGE_ENCODE] && ms[FC_STAGE_UPLOAD] >= 0.0f);
    fc_stream_image_free(&img);
    check_refresh(v, 1, pushed);

    /* Its own camera: the same frame again, then (quiet again) its refresh. */
    svc_axis_camera(4.5f, SIZE, SIZE, &cam);
    CHECK_CODE(fc_client_set_camera(v, &cam, &err), FC_OK);
    CHECK(next_non_refresh(v, &img));
    CHECK(img.view_change && img.frame_number == 1 && img.missed == 0);
    fc_stream_image_free(&img);

    /* RENDER on a viewer: the session's frame with its camera, never dropped. */
    fc_render_request depth = {.format = FC_FORMAT_RAW, .aov = FC_AOV_DEPTH};
    fc_image_result snapshot = {0};
    CHECK_CODE(fc_client_render(v, &depth, &snapshot, &err), FC_OK);
    CHECK_NEAR(svc_raw_centre(&snapshot), svc_axis_depth(4.5f, 0.0f), 0.01);
    fc_image_result_free(&snapshot);

    CHECK(push_frame(p, 0.0f));
    CHECK(next_non_refresh(v, &img));
    CHECK(img.frame_number == 2 && img.sequence == 2 && !img.view_change);
    fc_stream_image_free(&img);

    /* The producer vanishes: the session ends for the viewer, which stays on
     * the last frame (test_service_session_end.c goes on from there). */
    fc_client_close(p);
    CHECK(next_non_refresh(v, &img));
    CHECK(img.ended && img.image.data == NULL);
    fc_stream_image_free(&img);
    CHECK(fc_client_session_ended(v));

    /* The name is free again: a new session, with no frames yet. */
    fc_session_status status;
    fc_client *again = svc_client(d, "producer");
    CHECK(again && fc_client_publish(again, "gamma", &status, &err) == FC_OK);
    CHECK(status.frames == 0 && status.producers == 1 && status.viewers == 0);
    fc_client_close(again);
    fc_client_close(v);
}

static void test_viewer_leaves(const fc_test_daemon *d)
{
    fc_client *p = publisher(d, "delta");
    fc_client *v = svc_client(d, "viewer");
    fc_render_request raw = {.format = FC_FORMAT_RAW, .aov = FC_AOV_DEPTH};
    fc_error err;
    CHECK(push_frame(p, 0.0f));
    CHECK_CODE(fc_client_subscribe(v, "delta", &raw, SIZE, SIZE, NULL, &err), FC_OK);
    CHECK_CODE(fc_client_leave_session(v, &err), FC_OK);
    fc_stream_image img;
    CHECK_CODE(fc_client_next_image(v, &img, &err), FC_ERR_USAGE);
    CHECK(push_frame(p, 0.1f));
    /* Out of the session, the viewer has no frame of its own: nothing streams in between. */
    fc_image_result image = {0};
    CHECK_CODE(fc_client_render(v, &raw, &image, &err), FC_ERR_BAD_STATE);
    fc_client_close(v);
    fc_client_close(p);
}

/* The producer ends the session (its leave answered, so the daemon has sent the
 * viewer SESSION_END) before the viewer, which has not read it, leaves: the
 * viewer is still in the ended session (PROTOCOL.md 10.1), so the daemon answers
 * the leave, and no image follows it (fluidcast watch --count exited 5 on this
 * race when the daemon dropped the viewer with its SESSION_END). */
static void test_leave_after_the_end(const fc_test_daemon *d)
{
    fc_client *p = publisher(d, "ending");
    fc_client *v = svc_client(d, "viewer");
    fc_render_request raw = {.format = FC_FORMAT_RAW, .aov = FC_AOV_DEPTH};
    fc_error err;
    CHECK_CODE(fc_client_subscribe(v, "ending", &raw, SIZE, SIZE, NULL, &err), FC_OK);
    CHECK_CODE(fc_client_leave_session(p, &err), FC_OK);
    CHECK_MSG(fc_client_leave_session(v, &err) == FC_OK, "leave after the end: %s", err.message);
    fc_stream_image img;
    CHECK_CODE(fc_client_next_image(v, &img, &err), FC_ERR_USAGE);
    fc_client_close(v);
    fc_client_close(p);
}

int main(void)
{
    char dir[] = "/tmp/fc-service-XXXXXX";
    if (!mkdtemp(dir))
        return 1;
    char path[96];
    snprintf(path, sizeof path, "%s/fluidcastd.sock", dir);
    const char *const args[] = {"--max-image", "256x256", "--unix", path, "--refresh-ms", "300",
                                "--max-sessions", "3", NULL};
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, args);
    test_version_mismatch(&daemon);
    test_unix_socket(path);
    test_sessions_need_the_capability(&daemon);
    test_roles(&daemon);
    test_list_and_limit(&daemon);
    test_viewer_views_and_refresh(&daemon);
    test_viewer_leaves(&daemon);
    test_leave_after_the_end(&daemon);
    CHECK(svc_stop_daemon(&daemon));
    CHECK_MSG(access(path, F_OK) != 0, "the daemon left its socket file behind");
    rmdir(dir);
    return test_result();
}
