/* test_service_cli.c — the fluidcast command's stream, watch and info, and the
 * example producers, as real processes against the real fluidcastd: what they
 * print, the files they write, their exit codes, and that the frames a
 * watcher saw plus the ones it missed add up to the frames streamed. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "support/image_decode.h"
#include "test_ball.h"
#include "test_util.h"

enum { FILES = 4, SIZE = 41 };

static const char *const daemon_args[] = {"--max-image", "256x256", NULL};

typedef struct cli_job {
    const char *program;
    char dir[64];                 /* scratch: its captured output */
    const char *args[24];
    cli_result result;
} cli_job;

static void *run_job(void *arg)
{
    cli_job *job = arg;
    cli_run(job->program, job->dir, job->args, &job->result);
    return NULL;
}

static void make_dir(char *dir, size_t size, const char *base, const char *name)
{
    snprintf(dir, size, "%s/%s", base, name);
    mkdir(dir, 0700);
}

/* Waits until the session has `viewers` viewers (the watch process subscribed). */
static bool wait_for_viewers(const fc_test_daemon *d, const char *session, uint32_t viewers)
{
    fc_client *c = svc_client(d, "waiter");
    bool seen = false;
    for (int tries = 0; c && !seen && tries < 500; tries++) {
        fc_session_status *list = NULL;
        uint32_t count = 0;
        fc_error err;
        if (fc_client_list_sessions(c, &list, &count, &err) != FC_OK)
            break;
        for (uint32_t i = 0; i < count; i++)
            seen |= strcmp(list[i].name, session) == 0 && list[i].viewers == viewers;
        fc_session_list_free(list);
        if (!seen)
            svc_sleep_ms(20);
    }
    fc_client_close(c);
    return seen;
}

/* Adds up a watch run's "image N: frame F, ..., missed M" lines. */
static void tally_watch(const char *out, int *images, unsigned *missed, unsigned long long *last_frame)
{
    *images = 0;
    *missed = 0;
    *last_frame = 0;
    for (const char *line = out; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        int n;
        unsigned long long frame;
        unsigned m;
        const char *missed_at = strstr(line, "missed ");
        if (sscanf(line, "image %d: frame %llu,", &n, &frame) == 2 && missed_at &&
            sscanf(missed_at, "missed %u", &m) == 1) {
            (*images)++;
            *missed += m;
            *last_frame = frame;
        }
    }
}

static bool file_has_size(const char *path, size_t size)
{
    struct stat st;
    return stat(path, &st) == 0 && (size_t)st.st_size == size;
}

static void write_frames(const char *dir, char paths[FILES][96])
{
    for (int f = 0; f < FILES; f++) {
        fc_frame frame = {0};
        fc_error err;
        snprintf(paths[f], sizeof paths[f], "%s/frame%d.f32", dir, f);
        CHECK(svc_grid_frame(0.05f * (float)f, &frame, &err) == FC_OK && test_write_f32(&frame, paths[f]));
        fc_frame_free(&frame);
    }
}

/* The NAL unit types of an Annex B file: a bit per type present, and the number of slices (types 1 and 5). */
static uint32_t annex_b_types(const uint8_t *p, size_t n, int *slices)
{
    uint32_t types = 0;
    *slices = 0;
    for (size_t i = 0; i + 3 < n; i++)
        if (p[i] == 0 && p[i + 1] == 0 && p[i + 2] == 1) {
            int type = p[i + 3] & 0x1f;
            types |= 1u << type;
            *slices += type == 1 || type == 5;
            i += 2;
        }
    return types;
}

/* watch --format h264 --out-dir: the access units it printed, in one Annex B file starting with an IDR. */
static void check_h264_watch(const cli_job *video, const char *dir)
{
    CHECK_MSG(video->result.status == 0 && strstr(video->result.out, "session ended"), "watch h264: %d\n%s%s",
              video->result.status, video->result.out, video->result.err);
    int units = 0;
    for (const char *p = strstr(video->result.out, " H.264, "); p; p = strstr(p + 1, " H.264, "))
        units++;
    char path[128];
    snprintf(path, sizeof path, "%s/cli.h264", dir);
    size_t size = 0;
    uint8_t *data = read_whole_file(path, &size);
    int slices = 0;
    uint32_t types = data ? annex_b_types(data, size, &slices) : 0;
    static const uint8_t sps_start[] = {0, 0, 0, 1, 0x67};
    CHECK_MSG(data && size > sizeof sps_start && memcmp(data, sps_start, sizeof sps_start) == 0, "%s starts with %s",
              path, data ? "no SPS" : "nothing");
    CHECK_MSG((types & (1u << 5)) && (types & (1u << 8)) && units >= 1 && slices == units,
              "%s: NAL types 0x%x, %d slices for %d access units", path, types, slices, units);
    CHECK_MSG(strstr(video->result.out, "(key frame)") != NULL, "no key frame flagged:\n%s", video->result.out);
    free(data);
}

static void test_stream_watch_info(const fc_test_daemon *d, const char *base)
{
    char paths[FILES][96], out_dir[96], watch_dir[96], video_dir[96];
    write_frames(base, paths);
    snprintf(out_dir, sizeof out_dir, "%s/out", base);
    snprintf(watch_dir, sizeof watch_dir, "%s/watched", base);
    snprintf(video_dir, sizeof video_dir, "%s/video", base);
    const char *server = svc_address(d);

    cli_job watcher = {.program = FLUIDCAST_CLI_PATH,
                       .args = {"watch", "--server", server, "--session", "cli", "--size", "41x41", "--format", "raw",
                                "--out-dir", watch_dir, NULL}};
    cli_job counter = {.program = FLUIDCAST_CLI_PATH,
                       .args = {"watch", "--server", server, "--session", "cli", "--count", "1", "--format", "jpg",
                                "--quality", "80", "--size", "41x41", NULL}};
    cli_job video = {.program = FLUIDCAST_CLI_PATH,
                     .args = {"watch", "--server", server, "--session", "cli", "--size", "42x42", "--format", "h264",
                              "--out-dir", video_dir, NULL}};
    make_dir(watcher.dir, sizeof watcher.dir, base, "w1");
    make_dir(counter.dir, sizeof counter.dir, base, "w2");
    make_dir(video.dir, sizeof video.dir, base, "w3");
    pthread_t threads[3];
    pthread_create(&threads[0], NULL, run_job, &watcher);
    pthread_create(&threads[1], NULL, run_job, &counter);
    pthread_create(&threads[2], NULL, run_job, &video);
    CHECK_MSG(wait_for_viewers(d, "cli", 3), "the watchers never subscribed");

    cli_result info;
    const char *info_args[] = {"info", "--server", server, NULL};
    cli_run(FLUIDCAST_CLI_PATH, base, info_args, &info);
    CHECK_MSG(info.status == 0 && strstr(info.out, "fluidcastd 0.1.0 (protocol 1)") &&
                  strstr(info.out, "llvmpipe") && strstr(info.out, "capabilities: sessions zstd quantize16 device") &&
                  strstr(info.out, "device:       Mesa surfaceless platform (no device)") &&
                  strstr(info.out, "cli: 0 producer(s), 3 viewer(s), 0 frame(s)"),
              "info: status %d, out:\n%s", info.status, info.out);

    cli_result stream;
    const char *stream_args[] = {"stream", paths[0], paths[1], paths[2], paths[3], "--server", server, "--session",
                                 "cli", "--size", "41x41", "--radius", "0.05", "--zstd", "--out-dir", out_dir, NULL};
    cli_run(FLUIDCAST_CLI_PATH, base, stream_args, &stream);
    pthread_join(threads[0], NULL);
    pthread_join(threads[1], NULL);
    pthread_join(threads[2], NULL);
    check_h264_watch(&video, video_dir);

    CHECK_MSG(stream.status == 0, "stream: status %d, err: %s", stream.status, stream.err);
    CHECK_MSG(strstr(stream.out, "frame 1/4 ") && strstr(stream.out, "frame 4/4 ") &&
                  strstr(stream.out, "streamed 4 frames") && strstr(stream.out, "% saved)"),
              "stream out:\n%s", stream.out);
    for (int f = 1; f <= FILES; f++) {
        char path[128];
        snprintf(path, sizeof path, "%s/frame_%06d.png", out_dir, f);
        size_t size;
        uint8_t *png = read_whole_file(path, &size);
        fc_decoded_image decoded;
        fc_error err;
        CHECK_MSG(png && fc_decode_image(png, size, "png", 0, &decoded, &err) == FC_OK, "%s", path);
        if (png && decoded.pixels) {
            CHECK(decoded.width == SIZE && decoded.height == SIZE);
            fc_decoded_image_free(&decoded);
        }
        free(png);
    }

    int images;
    unsigned missed;
    unsigned long long last;
    tally_watch(watcher.result.out, &images, &missed, &last);
    CHECK_MSG(watcher.result.status == 0 && strstr(watcher.result.out, "session ended"), "watch: %d\n%s%s",
              watcher.result.status, watcher.result.out, watcher.result.err);
    CHECK_MSG(images >= 1 && images + missed == FILES && last == FILES, "watch: %d image(s), %u missed, last %llu",
              images, missed, last);
    char last_path[128];
    snprintf(last_path, sizeof last_path, "%s/cli_%06d.raw", watch_dir, FILES);
    CHECK_MSG(file_has_size(last_path, (size_t)SIZE * SIZE * 4), "%s", last_path);
    CHECK_MSG(counter.result.status == 0 && strstr(counter.result.out, "image 1: frame ") &&
                  strstr(counter.result.out, "JPEG") && strstr(counter.result.out, "1 image(s),") &&
                  !strstr(counter.result.out, "image 2:"),
              "watch --count 1: %d\n%s%s", counter.result.status, counter.result.out, counter.result.err);
}

static void test_usage_errors(const char *base)
{
    const char *no_files[] = {"stream", "--session", "x", NULL};
    const char *no_session[] = {"watch", "--count", "3", NULL};
    const char *png_quality[] = {"stream", "a.f32", "--quality", "50", NULL};
    const char *nobody[] = {"info", "--server", "127.0.0.1:1", NULL};
    const char *stream_h264[] = {"stream", "a.f32", "--format", "h264", NULL};
    const char *const *runs[] = {no_files, no_session, png_quality, nobody, stream_h264};
    const int expected[] = {2, 2, 2, 4, 2};
    for (int i = 0; i < 5; i++) {
        cli_result r;
        cli_run(FLUIDCAST_CLI_PATH, base, runs[i], &r);
        CHECK_MSG(r.status == expected[i] && strncmp(r.err, "fluidcast: ", 11) == 0, "%s %s: status %d, err %s",
                  runs[i][0], runs[i][1], r.status, r.err);
    }
}

/* An example producer against a watcher: both succeed and the frames add up. */
static void run_example(const fc_test_daemon *d, const char *base, const char *program, const char *session,
                        const char *frames, const char *ranks)
{
    const char *server = svc_address(d);
    cli_job watcher = {.program = FLUIDCAST_CLI_PATH,
                       .args = {"watch", "--server", server, "--session", session, "--size", "41x41", "--format",
                                "raw", NULL}};
    make_dir(watcher.dir, sizeof watcher.dir, base, session);
    pthread_t thread;
    pthread_create(&thread, NULL, run_job, &watcher);
    CHECK(wait_for_viewers(d, session, 1));
    cli_result producer;
    const char *args[] = {server, session, frames, ranks, NULL};
    cli_run(program, base, args, &producer);
    pthread_join(thread, NULL);
    int images;
    unsigned missed;
    unsigned long long last;
    tally_watch(watcher.result.out, &images, &missed, &last);
    unsigned expected = (unsigned)atoi(frames);
    CHECK_MSG(producer.status == 0, "%s: %d %s", program, producer.status, producer.err);
    CHECK_MSG(watcher.result.status == 0 && images >= 1 && images + missed == expected && last == expected,
              "%s: watch %d, %d image(s), %u missed, last %llu", session, watcher.result.status, images, missed,
              last);
}

int main(void)
{
    char base[] = "/tmp/fc-service-cli-XXXXXX";
    if (!mkdtemp(base))
        return 1;
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, daemon_args);
    test_stream_watch_info(&daemon, base);
    test_usage_errors(base);
    run_example(&daemon, base, EXAMPLE_PRODUCER_PATH, "example", "5", NULL);
    run_example(&daemon, base, EXAMPLE_PRODUCER_RANKS_PATH, "ranks", "4", "3");
    CHECK(svc_stop_daemon(&daemon));
    /* The scratch files are left for inspection only when something failed. */
    if (test_result() == 0) {
        char command[128];
        snprintf(command, sizeof command, "rm -rf %s", base);
        CHECK(system(command) == 0);
    }
    return test_result();
}
