/* test_service_slow_viewer.c — a viewer that stops reading (its receive
 * buffer small, so the server's output to it backs up at once) must not slow
 * the producer (timed with and without it, each time with a second viewer
 * that reads everything), nor that other viewer; the server must not queue
 * images for it; and when it reads again it gets the newest frame, told how
 * many it missed, so that images + missed account for every frame. */
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_util.h"

enum { FRAMES = 20, WIDTH = 129, HEIGHT = 97, STALLED_RECEIVE_BUFFER = 4096 };

static const char *const daemon_args[] = {"--max-image", "256x256", NULL};

static fc_render_request colour_raw(void)
{
    return (fc_render_request){.format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_COLOR};
}

/* Publishes FRAMES frames to `session`, each rendered back (a RENDER is never
 * dropped), and returns the milliseconds that took; leaves the session after. */
static double produce(const fc_test_daemon *d, const char *session)
{
    fc_client *c = svc_client(d, "producer");
    fc_error err;
    fc_camera cam;
    fc_settings settings;
    svc_axis_camera(3.0f, WIDTH, HEIGHT, &cam);
    svc_settings(&settings);
    fc_render_request request = colour_raw();
    bool ok = c && fc_client_publish(c, session, NULL, &err) == FC_OK &&
              fc_client_set_camera(c, &cam, &err) == FC_OK && fc_client_set_settings(c, &settings, &err) == FC_OK;
    double start = svc_now_ms();
    for (int f = 1; ok && f <= FRAMES; f++) {
        fc_frame frame = {0};
        fc_image_result image = {0};
        ok = svc_grid_frame(0.01f * (float)f, &frame, &err) == FC_OK &&
             fc_client_send_frame(c, &frame, &err) == FC_OK && fc_client_render(c, &request, &image, &err) == FC_OK &&
             image.size == (size_t)WIDTH * HEIGHT * 4;
        fc_image_result_free(&image);
        fc_frame_free(&frame);
    }
    double elapsed = svc_now_ms() - start;
    CHECK_MSG(ok && fc_client_leave_session(c, &err) == FC_OK, "producer of %s: %s", session, err.message);
    fc_client_close(c);
    return elapsed;
}

/* What one viewer received up to the session's end. */
typedef struct tally {
    int images;
    uint64_t missed;
    uint64_t last_frame;
    bool ended;
    bool sized_right;
} tally;

/* Reads one STREAM_IMAGE or the SESSION_END from a raw socket into the tally. */
static bool read_stream_message(int fd, uint32_t subscribe_id, tally *t)
{
    fc_test_message m;
    fc_error err;
    if (fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &m, &err) != FC_OK) {
        fprintf(stderr, "stalled viewer: %s\n", err.message);
        return false;
    }
    bool ok = m.header.request_id == subscribe_id;
    if (ok && m.header.type == FC_MSG_SESSION_END) {
        t->ended = true;
    } else if (ok && m.header.type == FC_MSG_STREAM_IMAGE) {
        fc_stream_tag tag;
        fc_image_reply image;
        ok = fc_wire_read_stream_image(m.payload, m.header.length, &tag, &image, &err) == FC_OK;
        t->images++;
        t->missed += tag.missed;
        t->last_frame = tag.frame_number;
        t->sized_right = t->sized_right && image.size == (size_t)WIDTH * HEIGHT * 4;
    } else {
        ok = false;
    }
    fc_test_message_free(&m);
    return ok;
}

/* Subscribes on a raw socket with a tiny receive buffer; returns it, unread. */
static int stalled_viewer(const fc_test_daemon *d, const char *session, uint32_t subscribe_id)
{
    fc_welcome welcome;
    int fd = svc_raw_connect(d->port, FC_CAP_SESSIONS, STALLED_RECEIVE_BUFFER, &welcome);
    if (fd < 0)
        return -1;
    fc_subscribe sub = {.request = colour_raw(), .width = WIDTH, .height = HEIGHT};
    snprintf(sub.name, sizeof sub.name, "%s", session);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_test_message state = {0};
    bool ok = fc_wire_write_subscribe(&b, subscribe_id, &sub, &err) == FC_OK && svc_send(fd, &b) &&
              fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &state, &err) == FC_OK &&
              state.header.type == FC_MSG_SESSION_STATE;
    fc_test_message_free(&state);
    fc_buf_free(&b);
    CHECK_MSG(ok, "stalled viewer could not subscribe");
    return fd;
}

typedef struct fast_viewer {
    const fc_test_daemon *daemon;
    const char *session;
    fc_client *client;
    tally seen;
} fast_viewer;

static void *read_everything(void *arg)
{
    fast_viewer *v = arg;
    fc_error err;
    while (!v->seen.ended) {
        fc_stream_image img;
        if (fc_client_next_image(v->client, &img, &err) != FC_OK) {
            fprintf(stderr, "fast viewer: %s\n", err.message);
            break;
        }
        v->seen.ended = img.ended;
        if (!img.ended) {
            v->seen.images++;
            v->seen.missed += img.missed;
            v->seen.last_frame = img.frame_number;
        }
        fc_stream_image_free(&img);
    }
    return NULL;
}

/* Runs a producer on `session` while a viewer reads everything; returns the producer's time. */
static double produce_with_fast_viewer(const fc_test_daemon *d, const char *session, fast_viewer *fast)
{
    *fast = (fast_viewer){.daemon = d, .session = session, .client = svc_client(d, "fast viewer")};
    fc_render_request request = colour_raw();
    fc_settings settings;
    svc_settings(&settings);
    fc_error err;
    CHECK(fast->client && fc_client_set_settings(fast->client, &settings, &err) == FC_OK &&
          fc_client_subscribe(fast->client, session, &request, WIDTH, HEIGHT, NULL, &err) == FC_OK);
    pthread_t thread;
    pthread_create(&thread, NULL, read_everything, fast);
    double ms = produce(d, session);
    pthread_join(thread, NULL);
    fc_client_close(fast->client);
    return ms;
}

static void test_stalled_viewer(const fc_test_daemon *d)
{
    fast_viewer fast;
    double without_ms = produce_with_fast_viewer(d, "without", &fast);
    const uint32_t subscribe_id = 7;
    int stalled = stalled_viewer(d, "watched", subscribe_id);
    double with_ms = produce_with_fast_viewer(d, "watched", &fast);

    /* A producer held up by the stalled viewer would not finish while it stays
     * stalled (it reads only below): that it finished is the check, not its time. */
    printf("producer: %.0f ms with a stalled viewer, %.0f ms without\n", with_ms, without_ms);
    CHECK_MSG(fast.seen.ended && fast.seen.last_frame == FRAMES && fast.seen.images + fast.seen.missed == FRAMES,
              "fast viewer: %d image(s), %llu missed, last frame %llu", fast.seen.images,
              (unsigned long long)fast.seen.missed, (unsigned long long)fast.seen.last_frame);

    /* Reading again: what the kernel buffered, then the newest frame, then the end. */
    tally t = {.sized_right = true};
    while (stalled >= 0 && !t.ended && read_stream_message(stalled, subscribe_id, &t))
        ;
    CHECK_MSG(t.ended, "the stalled viewer never got SESSION_END");
    CHECK_MSG(t.last_frame == FRAMES, "its last image shows frame %llu", (unsigned long long)t.last_frame);
    CHECK_MSG(t.images + t.missed == FRAMES, "%d image(s) + %llu missed != %d", t.images,
              (unsigned long long)t.missed, FRAMES);
    CHECK_MSG(t.missed > 0 && t.images < FRAMES / 2, "stalled viewer: %d image(s), %llu missed", t.images,
              (unsigned long long)t.missed);
    CHECK(t.sized_right);
    printf("producer %.0f ms without, %.0f ms with a stalled viewer; stalled viewer: %d image(s), %llu missed\n",
           without_ms, with_ms, t.images, (unsigned long long)t.missed);
    if (stalled >= 0)
        close(stalled);
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, daemon_args);
    test_stalled_viewer(&daemon);
    CHECK(svc_stop_daemon(&daemon));
    return test_result();
}
