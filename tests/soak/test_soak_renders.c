/* test_soak_renders.c — a bounded soak of the real fluidcastd: 8 libfluidcast
 * clients each push 1500 frames (every one moved from the last) and render each
 * as a tiny image in PNG, JPEG, EXR or RAW, concurrently, until 12000 frames are
 * done (or the time budget is spent). Every request must be answered with an
 * image of the requested size and format that decodes independently, and the
 * daemon's resident memory must not keep growing once it is warm: leaking one
 * 32x32 RGBA image (4 KiB) per render would exceed the bound many times over. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "support/image_decode.h"
#include "support/test_scene.h"
#include "test_util.h"

enum {
    CLIENTS = 8,
    SIZE = 32,
    WARMUP_RENDERS = 15,          /* per client, before the baseline RSS sample */
    RENDERS_PER_CLIENT = 1500,    /* frames, each rendered once: 12000 in all */
    MIN_RENDERS_PER_CLIENT = 40,  /* fewer means the daemon stalled, not just a slow machine */
    MAX_RSS_GROWTH_KB = 10 * 1024
};
/* Wall-clock budget for the measured phase, so a slow shared machine ends early instead of timing out. */
static const double SOAK_BUDGET_MS = 120000.0;

typedef struct soak_worker {
    int index;
    pthread_barrier_t *warm;      /* every client warmed up: the baseline is sampled between the two waits */
    double deadline_ms;           /* set by the main thread before releasing the second wait */
    fc_client *client;
    fc_frame frame;               /* this client's particles, nudged before every send */
    int renders;                  /* answered with a valid image */
    int failures;
} soak_worker;

static const fc_image_format FORMATS[] = {FC_FORMAT_PNG, FC_FORMAT_JPEG, FC_FORMAT_EXR, FC_FORMAT_RAW};
static const char *const EXTENSIONS[] = {"png", "jpg", "exr", NULL};

/* Resident set size of a process in KiB, from /proc/PID/status; -1 when unreadable. */
static long resident_kb(pid_t pid)
{
    char path[64], line[256];
    snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    long kb = -1;
    while (kb < 0 && fgets(line, sizeof line, f))
        if (strncmp(line, "VmRSS:", 6) == 0)
            kb = strtol(line + 6, NULL, 10);
    fclose(f);
    return kb;
}

/* The image is what was asked for: header fields, and bytes that decode to SIZE x SIZE
 * (RAW colour is exactly RGBA8 rows). */
static bool image_valid(const fc_image_result *img, size_t format_index, fc_error *err)
{
    if (img->width != SIZE || img->height != SIZE || img->format != FORMATS[format_index] || img->aov != FC_AOV_COLOR)
        return fc_error_set(err, FC_ERR_PROTOCOL, "got %ux%u format %d aov %d", img->width, img->height,
                            (int)img->format, (int)img->aov), false;
    if (!EXTENSIONS[format_index])
        return img->size == (size_t)SIZE * SIZE * 4 ||
               (fc_error_set(err, FC_ERR_PROTOCOL, "RAW image of %zu bytes", img->size), false);
    fc_decoded_image decoded;
    if (fc_decode_image(img->data, img->size, EXTENSIONS[format_index], 0, &decoded, err) != FC_OK)
        return false;
    bool sized = decoded.width == SIZE && decoded.height == SIZE;
    if (!sized)
        fc_error_set(err, FC_ERR_PROTOCOL, "%s decodes to %ux%u", EXTENSIONS[format_index], decoded.width,
                     decoded.height);
    fc_decoded_image_free(&decoded);
    return sized;
}

/* One new frame, rendered in the format this client's turn picks; counts the outcome. */
static void render_once(soak_worker *w, int turn)
{
    size_t format_index = (size_t)(w->index + turn) % 4;
    fc_render_request request = {.format = FORMATS[format_index], .quality = 90, .aov = FC_AOV_COLOR};
    fc_image_result img = {0};
    fc_error err;
    /* Back and forth along x, so every frame differs from the last and the particles stay in view. */
    float nudge = turn % 2 ? 0.01f : -0.01f;
    for (uint64_t i = 0; i < w->frame.count; i++)
        w->frame.positions[3 * i] += nudge;
    if (fc_client_send_frame(w->client, &w->frame, &err) == FC_OK &&
        fc_client_render(w->client, &request, &img, &err) == FC_OK && image_valid(&img, format_index, &err)) {
        w->renders++;
    } else if (w->failures++ < 3) {
        fprintf(stderr, "client %d render %d (%s): %s\n", w->index, turn, EXTENSIONS[format_index] ? EXTENSIONS[format_index] : "raw",
                err.message);
    }
    fc_image_result_free(&img);
}

static bool make_scene(soak_worker *w)
{
    fc_camera camera;
    fc_error err;
    fc_test_front_camera(SIZE, SIZE, &camera);
    bool ok = fc_test_cube_frame(&w->frame, &err) == FC_OK && fc_client_set_camera(w->client, &camera, &err) == FC_OK;
    if (!ok)
        fprintf(stderr, "scene: %s\n", err.message);
    return ok;
}

static void *soak_client(void *arg)
{
    soak_worker *w = arg;
    bool ready = w->client && make_scene(w);
    int turn = 0;
    for (; ready && turn < WARMUP_RENDERS; turn++)
        render_once(w, turn);
    pthread_barrier_wait(w->warm);
    pthread_barrier_wait(w->warm);
    for (; ready && turn < RENDERS_PER_CLIENT && svc_now_ms() < w->deadline_ms; turn++)
        render_once(w, turn);
    fc_frame_free(&w->frame);
    return NULL;
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, NULL);
    pthread_barrier_t warm;
    pthread_barrier_init(&warm, NULL, CLIENTS + 1);
    soak_worker workers[CLIENTS];
    pthread_t threads[CLIENTS];
    for (int i = 0; i < CLIENTS; i++) {
        workers[i] = (soak_worker){.index = i, .warm = &warm, .client = svc_client(&daemon, "soak")};
        CHECK_MSG(workers[i].client, "client %d could not connect", i);
        pthread_create(&threads[i], NULL, soak_client, &workers[i]);
    }
    pthread_barrier_wait(&warm);
    long baseline_kb = resident_kb(daemon.pid);
    double started_ms = svc_now_ms();
    for (int i = 0; i < CLIENTS; i++)
        workers[i].deadline_ms = started_ms + SOAK_BUDGET_MS;
    pthread_barrier_wait(&warm);

    int total = 0, failures = 0;
    for (int i = 0; i < CLIENTS; i++) {
        pthread_join(threads[i], NULL);
        total += workers[i].renders;
        failures += workers[i].failures;
        CHECK_MSG(workers[i].renders >= MIN_RENDERS_PER_CLIENT, "client %d: only %d renders", i, workers[i].renders);
    }
    double elapsed_s = (svc_now_ms() - started_ms) / 1000.0;
    long final_kb = resident_kb(daemon.pid);
    printf("soak: %d frames rendered (%d after warm-up), %d failed, %.1f s measured, %.1f renders/s\n", total,
           total - CLIENTS * WARMUP_RENDERS, failures, elapsed_s, (total - CLIENTS * WARMUP_RENDERS) / elapsed_s);
    printf("soak: daemon RSS %ld KiB after warm-up, %ld KiB at the end: growth %ld KiB (bound %d KiB)\n",
           baseline_kb, final_kb, final_kb - baseline_kb, MAX_RSS_GROWTH_KB);
    CHECK_MSG(failures == 0, "%d request(s) not answered with a valid image", failures);
    CHECK(baseline_kb > 0 && final_kb > 0);
    CHECK_MSG(final_kb - baseline_kb < MAX_RSS_GROWTH_KB, "RSS grew by %ld KiB", final_kb - baseline_kb);

    for (int i = 0; i < CLIENTS; i++)
        fc_client_close(workers[i].client);
    pthread_barrier_destroy(&warm);
    CHECK_MSG(svc_stop_daemon(&daemon), "fluidcastd did not exit 0 after the soak");
    return test_result();
}
