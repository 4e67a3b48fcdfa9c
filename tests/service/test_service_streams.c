/* test_service_streams.c — P producers and V viewers at once, each on its own
 * connection and thread, against the real fluidcastd. Every image a viewer
 * gets must show the frame it says it shows (depth at the centre, known
 * analytically from the frame number and the viewer's own camera), frames go
 * forward only, the images plus the frames missed account for every frame
 * published, and the producer's end reaches every viewer as SESSION_END. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_util.h"

enum { PRODUCERS = 2, VIEWERS = 4, FRAMES = 6, SIZE = 41 };

static const char *const daemon_args[] = {"--max-image", "256x256", NULL};

/* Producer p moves its grid along z by dz(p, f) in frame f. */
static float frame_shift(int producer, uint64_t frame)
{
    return (producer == 0 ? 0.05f : -0.04f) * (float)frame;
}

typedef struct producer_run {
    const fc_test_daemon *daemon;
    int index;
    char session[16];
    int failures;
} producer_run;

typedef struct viewer_run {
    const fc_test_daemon *daemon;
    int producer;            /* whose session it watches */
    float eye_z;             /* its own camera */
    char session[16];
    bool subscribed;         /* set before the producers start */
    int images;
    uint64_t missed;
    uint64_t last_frame;
    bool ended;
    int bad_depth;
    int backwards;
    int failures;
} viewer_run;

static pthread_mutex_t subscribed_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t subscribed_cond = PTHREAD_COND_INITIALIZER;

static fc_render_request depth_request(void)
{
    return (fc_render_request){.format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_DEPTH};
}

/* Publishes FRAMES frames, rendering each back (which paces it like a
 * simulation that looks at its own output), then leaves. */
static void *produce(void *arg)
{
    producer_run *run = arg;
    fc_client *c = svc_client(run->daemon, "producer");
    fc_error err;
    fc_camera cam;
    fc_settings settings;
    svc_axis_camera(3.0f, SIZE, SIZE, &cam);
    svc_settings(&settings);
    if (!c || fc_client_publish(c, run->session, NULL, &err) != FC_OK ||
        fc_client_set_camera(c, &cam, &err) != FC_OK || fc_client_set_settings(c, &settings, &err) != FC_OK) {
        run->failures++;
        fc_client_close(c);
        return NULL;
    }
    for (uint64_t f = 1; f <= FRAMES; f++) {
        fc_frame frame = {0};
        fc_image_result image = {0};
        fc_render_request request = depth_request();
        float dz = frame_shift(run->index, f);
        if (svc_grid_frame(dz, &frame, &err) != FC_OK || fc_client_send_frame(c, &frame, &err) != FC_OK ||
            fc_client_render(c, &request, &image, &err) != FC_OK)
            run->failures++;
        else if (fabs(svc_raw_centre(&image) - svc_axis_depth(3.0f, dz)) > 0.01)
            run->failures++;
        fc_image_result_free(&image);
        fc_frame_free(&frame);
    }
    if (fc_client_leave_session(c, &err) != FC_OK)
        run->failures++;
    fc_client_close(c);
    return NULL;
}

static void check_image(viewer_run *run, const fc_stream_image *img)
{
    if (img->refresh || img->view_change)
        return;
    run->images++;
    run->missed += img->missed;
    if (img->frame_number <= run->last_frame)
        run->backwards++;
    run->last_frame = img->frame_number;
    double expected = svc_axis_depth(run->eye_z, frame_shift(run->producer, img->frame_number));
    if (fabs(svc_raw_centre(&img->image) - expected) > 0.01)
        run->bad_depth++;
}

static void mark_subscribed(viewer_run *run)
{
    pthread_mutex_lock(&subscribed_lock);
    run->subscribed = true;
    pthread_cond_broadcast(&subscribed_cond);
    pthread_mutex_unlock(&subscribed_lock);
}

/* Subscribes with its own camera and reads until the session ends. */
static void *view(void *arg)
{
    viewer_run *run = arg;
    fc_client *c = svc_client(run->daemon, "viewer");
    fc_error err;
    fc_camera cam;
    fc_settings settings;
    svc_axis_camera(run->eye_z, SIZE, SIZE, &cam);
    svc_settings(&settings);
    fc_render_request request = depth_request();
    bool ok = c && fc_client_set_camera(c, &cam, &err) == FC_OK &&
              fc_client_set_settings(c, &settings, &err) == FC_OK &&
              fc_client_subscribe(c, run->session, &request, SIZE, SIZE, NULL, &err) == FC_OK;
    mark_subscribed(run);
    while (ok && !run->ended) {
        fc_stream_image img;
        ok = fc_client_next_image(c, &img, &err) == FC_OK;
        if (ok && img.ended)
            run->ended = true;
        else if (ok)
            check_image(run, &img);
        fc_stream_image_free(&img);
    }
    if (!ok) {
        fprintf(stderr, "viewer of %s: %s\n", run->session, err.message);
        run->failures++;
    }
    fc_client_close(c);
    return NULL;
}

static void wait_subscribed(viewer_run *viewers)
{
    pthread_mutex_lock(&subscribed_lock);
    for (int v = 0; v < VIEWERS; v++)
        while (!viewers[v].subscribed)
            pthread_cond_wait(&subscribed_cond, &subscribed_lock);
    pthread_mutex_unlock(&subscribed_lock);
}

static void test_producers_and_viewers(const fc_test_daemon *daemon)
{
    producer_run producers[PRODUCERS];
    viewer_run viewers[VIEWERS];
    pthread_t threads[PRODUCERS + VIEWERS];
    for (int v = 0; v < VIEWERS; v++) {
        /* Two viewers per session, each with a camera of its own. */
        viewers[v] = (viewer_run){.daemon = daemon, .producer = v % PRODUCERS, .eye_z = v < PRODUCERS ? 3.0f : 4.5f};
        snprintf(viewers[v].session, sizeof viewers[v].session, "sim-%d", viewers[v].producer);
        pthread_create(&threads[PRODUCERS + v], NULL, view, &viewers[v]);
    }
    wait_subscribed(viewers);
    for (int p = 0; p < PRODUCERS; p++) {
        producers[p] = (producer_run){.daemon = daemon, .index = p};
        snprintf(producers[p].session, sizeof producers[p].session, "sim-%d", p);
        pthread_create(&threads[p], NULL, produce, &producers[p]);
    }
    for (int t = 0; t < PRODUCERS + VIEWERS; t++)
        pthread_join(threads[t], NULL);
    for (int p = 0; p < PRODUCERS; p++)
        CHECK_MSG(producers[p].failures == 0, "producer %d: %d failure(s)", p, producers[p].failures);
    for (int v = 0; v < VIEWERS; v++) {
        const viewer_run *r = &viewers[v];
        CHECK_MSG(r->failures == 0 && r->ended, "viewer %d: %d failure(s), ended %d", v, r->failures, r->ended);
        CHECK_MSG(r->images >= 1 && r->bad_depth == 0, "viewer %d: %d image(s), %d with the wrong depth", v,
                  r->images, r->bad_depth);
        CHECK_MSG(r->backwards == 0, "viewer %d: frames went backwards %d time(s)", v, r->backwards);
        CHECK_MSG(r->last_frame == FRAMES, "viewer %d: last frame %llu", v, (unsigned long long)r->last_frame);
        CHECK_MSG(r->images + r->missed == FRAMES, "viewer %d: %d image(s) + %llu missed != %d frames", v,
                  r->images, (unsigned long long)r->missed, FRAMES);
    }
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, daemon_args);
    test_producers_and_viewers(&daemon);
    CHECK(svc_stop_daemon(&daemon));
    return test_result();
}
