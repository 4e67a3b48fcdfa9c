/* e2e_stream.c — the streaming half of fluidcast-e2e-bench. The producer
 * records when it started sending each frame; the viewer looks the time up by
 * the frame number its stream image carries. */
#include "e2e_stream.h"

#include <pthread.h>
#include <stdlib.h>
#include <time.h>

#include "fc_error.h"
#include "fluidcast.h"

/* A viewer waits at most this long for one image; llvmpipe renders 1M particles in seconds. */
#define VIEWER_TIMEOUT_MS 120000u
/* Rejections of pushed frames are read back this often (cheap, but not free). */
#define POLL_EVERY_FRAMES 64

typedef struct push_log {
    pthread_mutex_t lock;     /* the producer appends while the viewer looks up */
    double *start_ms;         /* [frame number - 1] */
    uint64_t count, capacity;
} push_log;

typedef struct viewer_run {
    fc_client *client;
    push_log *log;
    e2e_samples latency;
    uint64_t received, skipped;
    double last_image_ms;
    fc_code code;
    fc_error err;
} viewer_run;

static fc_code push_log_add(push_log *log, double ms, fc_error *err)
{
    fc_code code = FC_OK;
    pthread_mutex_lock(&log->lock);
    if (log->count == log->capacity) {
        uint64_t capacity = log->capacity ? 2 * log->capacity : 1024;
        double *grown = realloc(log->start_ms, capacity * sizeof *grown);
        if (grown) {
            log->start_ms = grown;
            log->capacity = capacity;
        } else {
            code = fc_error_set(err, FC_ERR_NOMEM, "no memory for %llu push times", (unsigned long long)capacity);
        }
    }
    if (code == FC_OK)
        log->start_ms[log->count++] = ms;
    pthread_mutex_unlock(&log->lock);
    return code;
}

/* When frame `number` started out; FC_ERR_PROTOCOL for a number never pushed. */
static fc_code push_log_find(push_log *log, uint64_t number, double *ms, fc_error *err)
{
    pthread_mutex_lock(&log->lock);
    uint64_t count = log->count;
    if (number >= 1 && number <= count)
        *ms = log->start_ms[number - 1];
    pthread_mutex_unlock(&log->lock);
    if (number < 1 || number > count)
        return fc_error_set(err, FC_ERR_PROTOCOL, "stream image of frame %llu, but %llu frames were pushed",
                            (unsigned long long)number, (unsigned long long)count);
    return FC_OK;
}

static fc_code take_image(viewer_run *v, const fc_stream_image *img, double now)
{
    /* A refresh or view image shows a frame already counted. */
    if (img->refresh || img->view_change)
        return FC_OK;
    double pushed_ms = 0;
    fc_code code = push_log_find(v->log, img->frame_number, &pushed_ms, &v->err);
    if (code != FC_OK)
        return code;
    v->received++;
    v->skipped += img->missed;
    v->last_image_ms = now;
    return e2e_samples_add(&v->latency, now - pushed_ms, &v->err);
}

static void *viewer_main(void *arg)
{
    viewer_run *v = arg;
    for (;;) {
        fc_stream_image img = {0};
        v->code = fc_client_next_image(v->client, &img, &v->err);
        double now = e2e_now_ms();
        int ended = img.ended;
        if (v->code == FC_OK && !ended)
            v->code = take_image(v, &img, now);
        fc_stream_image_free(&img);
        if (v->code != FC_OK || ended)
            return NULL;
    }
}

static void sleep_until_ms(double when)
{
    double wait = when - e2e_now_ms();
    if (wait <= 0)
        return;
    long long ns = (long long)(wait * 1e6);
    struct timespec pause = {(time_t)(ns / 1000000000LL), (long)(ns % 1000000000LL)};
    nanosleep(&pause, NULL);
}

/* Pushes nudged frames for plan->seconds (at a fixed rate: those due before
 * the end, then waits for it); returns the time of the first push. */
static fc_code push_frames(fc_client *producer, e2e_scene *scene, const e2e_stream_plan *plan, push_log *log,
                           e2e_stream_result *out, double *first_ms, fc_error *err)
{
    double start = e2e_now_ms(), end = start + plan->seconds * 1e3;
    *first_ms = start;
    fc_code code = FC_OK;
    for (uint64_t i = 0; code == FC_OK; i++) {
        double due = plan->push_fps > 0 ? start + 1e3 * (double)i / plan->push_fps : e2e_now_ms();
        if (due >= end)
            break;
        sleep_until_ms(due);
        e2e_scene_nudge(scene, i);
        if ((code = push_log_add(log, e2e_now_ms(), err)) != FC_OK)
            break;
        code = fc_client_upload_frame(producer, &scene->frame, NULL, NULL, err);
        if (code == FC_OK && i % POLL_EVERY_FRAMES == 0)
            code = fc_client_poll_errors(producer, err);
    }
    sleep_until_ms(end);
    out->pushed = log->count;
    out->push_seconds = (e2e_now_ms() - start) / 1e3;
    out->push_fps = out->pushed / out->push_seconds;
    return code;
}

static fc_code connect_viewer(const e2e_stream_plan *plan, const e2e_config *cfg, const e2e_scene *scene,
                              fc_client **viewer, fc_error *err)
{
    fc_connect_options options = {.client_name = "e2e-bench viewer", .reply_timeout_ms = VIEWER_TIMEOUT_MS};
    /* A viewer's stream asks for 4:2:0 JPEG as fluidcast view does (--stream-jpeg-subsampling). */
    fc_settings settings = scene->settings;
    settings.jpeg_subsampling = cfg->stream_subsampling;
    fc_code code = fc_client_connect(plan->address, &options, viewer, err);
    if (code == FC_OK && (code = fc_client_set_settings(*viewer, &settings, err)) == FC_OK &&
        (code = fc_client_set_camera(*viewer, &scene->camera, err)) == FC_OK)
        code = fc_client_subscribe(*viewer, plan->session, &cfg->request, cfg->width, cfg->height, NULL, err);
    return code;
}

/* The producer's whole life: connect, publish, push, leave. */
static fc_code produce(const e2e_stream_plan *plan, e2e_scene *scene, push_log *log, e2e_stream_result *out,
                       double *first_ms, fc_error *err)
{
    fc_connect_options options = {.client_name = "e2e-bench producer"};
    fc_client *producer = NULL;
    fc_code code = fc_client_connect(plan->address, &options, &producer, err);
    if (code == FC_OK && (code = fc_client_publish(producer, plan->session, NULL, err)) == FC_OK &&
        (code = push_frames(producer, scene, plan, log, out, first_ms, err)) == FC_OK)
        code = fc_client_leave_session(producer, err);
    fc_client_close(producer);
    return code;
}

static void summarize(viewer_run *v, double first_ms, double push_ms, e2e_stream_result *out)
{
    out->received = v->received;
    out->skipped = v->skipped;
    out->in_flight = (int64_t)out->pushed - (int64_t)v->received - (int64_t)v->skipped;
    double span_ms = v->last_image_ms - first_ms;
    if (span_ms < push_ms)
        span_ms = push_ms;
    out->viewer_fps = v->received && span_ms > 0 ? v->received / (span_ms / 1e3) : 0;
    e2e_latency_summarize(&v->latency, &out->latency);
}

static fc_code run_with_viewer(const e2e_stream_plan *plan, e2e_scene *scene, viewer_run *v,
                               e2e_stream_result *out, fc_error *err)
{
    pthread_t thread;
    if (pthread_create(&thread, NULL, viewer_main, v) != 0)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot start the viewer thread");
    double first_ms = 0;
    fc_code code = produce(plan, scene, v->log, out, &first_ms, err);
    /* The viewer returns once the session ended: the producer left it, or
     * failed and was closed (which ends it too). A producer that never got to
     * PUBLISH leaves the viewer to its reply timeout. */
    pthread_join(thread, NULL);
    if (code == FC_OK && v->code != FC_OK) {
        *err = v->err;
        code = v->code;
    }
    summarize(v, first_ms, out->push_seconds * 1e3, out);
    return code;
}

fc_code e2e_run_stream(const e2e_stream_plan *plan, const e2e_config *cfg, e2e_stream_result *out, fc_error *err)
{
    *out = (e2e_stream_result){0};
    e2e_scene scene;
    fc_code code = e2e_scene_make(cfg, &scene, err);
    if (code != FC_OK)
        return code;
    push_log log = {.lock = PTHREAD_MUTEX_INITIALIZER};
    viewer_run v = {.log = &log};
    /* Subscribed before the first push, so every frame pushed is either received or counted missed. */
    if ((code = connect_viewer(plan, cfg, &scene, &v.client, err)) == FC_OK)
        code = run_with_viewer(plan, &scene, &v, out, err);
    fc_client_close(v.client);
    e2e_samples_free(&v.latency);
    free(log.start_ms);
    e2e_scene_free(&scene);
    return code;
}
