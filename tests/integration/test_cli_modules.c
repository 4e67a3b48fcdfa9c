/* test_cli_modules.c — the fluidcast command loads its heavy libraries only
 * for the commands that use them (client/cli/cli_module.h): the real binary,
 * traced by the dynamic loader (LD_DEBUG=files), against the real fluidcastd.
 *   - --version and a whole snapshot (a --background image included: the server
 *     decodes it) load neither OpenImageIO nor libav;
 *   - --legend loads fluidcast-image.so and OpenImageIO (and with it libav) and draws the legend;
 *     a render to .mp4 loads fluidcast-video.so and libavformat and writes an MP4; `view` runs
 *     from fluidcast-view.so with SDL2 (its window and pictures: tests/viewer); an HDF5 file is
 *     read through fluidcast-hdf5.so and libhdf5 (its contents: cli_hdf5);
 *   - with FLUIDCAST_MODULE_DIR on an empty directory, or on modules that are
 *     not what they should be, exactly those fail (exit 6, `view` 2, HDF5 input 3;
 *     the module and the loader's reason named) and everything else still works. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "image_encoder.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "test_ball.h"
#include "test_util.h"
#include "wire.h"

#define PATH_SIZE 384   /* the scratch directory and any file name */

typedef struct test_env {
    char dir[64];       /* scratch: particle files, images, loader traces */
    char server[32];    /* HOST:PORT of the daemon */
    unsigned traces;    /* traces taken so far, for unique names */
} test_env;

static const char *scratch(const test_env *env, const char *name, char out[PATH_SIZE])
{
    snprintf(out, PATH_SIZE, "%s/%s", env->dir, name);
    return out;
}

/* ---- runs, traced by the dynamic loader ---- */

typedef struct traced_run {
    cli_result r;
    char *trace;   /* the loader's LD_DEBUG=files output (malloc'd, "" when none) */
} traced_run;

/* The file LD_DEBUG_OUTPUT=prefix produced (prefix.PID), read whole and removed. */
static char *take_trace(const test_env *env, const char *stem)
{
    DIR *d = opendir(env->dir);
    char *text = NULL;
    struct dirent *e;
    size_t stem_len = strlen(stem);
    while (d && !text && (e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, stem, stem_len) != 0 || e->d_name[stem_len] != '.')
            continue;
        char path[PATH_SIZE];
        size_t size = 0;
        uint8_t *data = read_whole_file(scratch(env, e->d_name, path), &size);
        text = data ? realloc(data, size + 1) : NULL;
        if (text)
            text[size] = '\0';
        else
            free(data);
        unlink(path);
    }
    if (d)
        closedir(d);
    return text ? text : calloc(1, 1);
}

/* Runs the command with `module_dir` as FLUIDCAST_MODULE_DIR (NULL: unset). */
static void run_traced(test_env *env, const char *module_dir, const char *const *args, traced_run *t)
{
    char stem[32], prefix[PATH_SIZE];
    snprintf(stem, sizeof stem, "ld-trace-%u", env->traces++);
    setenv("LD_DEBUG", "files", 1);
    setenv("LD_DEBUG_OUTPUT", scratch(env, stem, prefix), 1);
    if (module_dir)
        setenv("FLUIDCAST_MODULE_DIR", module_dir, 1);
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, &t->r);
    unsetenv("LD_DEBUG");
    unsetenv("LD_DEBUG_OUTPUT");
    unsetenv("FLUIDCAST_MODULE_DIR");
    t->trace = take_trace(env, stem);
    /* The loader traced this run: else every "not loaded" below would hold vacuously. */
    CHECK_MSG(strstr(t->trace, "libc.so.6") != NULL, "no loader trace for %s %s", args[0], args[1] ? args[1] : "");
}

static bool loaded(const traced_run *t, const char *library)
{
    return strstr(t->trace, library) != NULL;
}

/* The libraries a command that reads, renders and writes a PNG never needs. */
static const char *const heavy[] = {"libOpenImageIO.so", "libavformat.so", "libavcodec.so", "libSDL2", "libhdf5",
                                    "fluidcast-image.so", "fluidcast-video.so", "fluidcast-view.so",
                                    "fluidcast-hdf5.so"};

static void check_light(const traced_run *t, const char *what)
{
    for (size_t i = 0; i < sizeof heavy / sizeof heavy[0]; i++)
        CHECK_MSG(!loaded(t, heavy[i]), "%s loaded %s", what, heavy[i]);
}

/* ---- fixtures ---- */

/* The ball with a velocity column (every fourth particle moving up at 3), for --color-by speed. */
static bool write_ball_csv(const fc_frame *ball, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    fputs("x,y,z,vx,vy,vz\n", f);
    for (uint64_t i = 0; i < ball->count; i++) {
        const float *p = &ball->positions[3 * i];
        fprintf(f, "%.9g,%.9g,%.9g,0,0,%d\n", (double)p[0], (double)p[1], (double)p[2], i % 4 ? 0 : 3);
    }
    return fclose(f) == 0;
}

/* A 16x16 pure red PNG, the background of a snapshot (fc_encode, linked into this test only). */
static bool write_red_png(const char *path)
{
    uint8_t pixels[16 * 16 * 4];
    for (size_t i = 0; i < sizeof pixels; i += 4) {
        pixels[i] = 255;
        pixels[i + 1] = pixels[i + 2] = 0;
        pixels[i + 3] = 255;
    }
    fc_image img = {.width = 16, .height = 16, .channels = 4, .type = FC_PIXEL_U8, .pixels = pixels};
    fc_buf png;
    fc_buf_init(&png);
    fc_error err;
    bool ok = fc_encode_image(&img, FC_FORMAT_PNG, 90, &png, &err) == FC_OK;
    FILE *f = ok ? fopen(path, "wb") : NULL;
    ok = f && fwrite(png.data, 1, png.len, f) == png.len;
    if (f)
        ok = fclose(f) == 0 && ok;
    fc_buf_free(&png);
    return ok;
}

static bool write_fixtures(const test_env *env)
{
    char path[PATH_SIZE];
    fc_frame ball = {0};
    bool ok = test_ball_frame(&ball, NULL) == FC_OK && test_write_f32(&ball, scratch(env, "ball.f32", path)) &&
              write_ball_csv(&ball, scratch(env, "ballv.csv", path)) && write_red_png(scratch(env, "red.png", path));
    fc_frame_free(&ball);
    /* Module directories: empty; and one whose modules are the wrong files. */
    ok = ok && mkdir(scratch(env, "no-modules", path), 0700) == 0 && mkdir(scratch(env, "bad-modules", path), 0700) == 0;
    FILE *f = fopen(scratch(env, "bad-modules/fluidcast-video.so", path), "w");
    ok = ok && f && fputs("not a shared object\n", f) >= 0;
    if (f)
        ok = fclose(f) == 0 && ok;
    /* A real module under the other's name: it loads but lacks fc_image_module_v1. */
    ok = ok && symlink(FC_BUILD_MODULE_DIR "/fluidcast-video.so", scratch(env, "bad-modules/fluidcast-image.so", path)) == 0;
    return ok;
}

static bool decode_png(const char *path, fc_decoded_image *img)
{
    size_t size = 0;
    uint8_t *data = read_whole_file(path, &size);
    fc_error err;
    fc_code code = data ? fc_decode_image(data, size, "png", false, img, &err) : FC_ERR_IO;
    free(data);
    CHECK_MSG(code == FC_OK, "%s is not a PNG", path);
    return code == FC_OK;
}

/* ---- the tests ---- */

static void test_version(test_env *env)
{
    traced_run t;
    run_traced(env, NULL, (const char *const[]){"--version", NULL}, &t);
    CHECK_CODE(t.r.status, 0);
    CHECK(strncmp(t.r.out, "fluidcast ", 10) == 0);
    check_light(&t, "--version");
    free(t.trace);
}

/* A whole snapshot over a scene image: the client only sends the file, the server decodes it. */
static void test_snapshot_is_light(test_env *env)
{
    char in[PATH_SIZE], out[PATH_SIZE], bg[PATH_SIZE];
    traced_run t;
    run_traced(env, NULL,
               (const char *const[]){"snapshot", scratch(env, "ball.f32", in), "-o", scratch(env, "bg.png", out),
                                     "--server", env->server, "--size", "64x48", "--background",
                                     scratch(env, "red.png", bg), NULL},
               &t);
    CHECK_MSG(t.r.status == 0, "snapshot: exit %d: %s", t.r.status, t.r.err);
    check_light(&t, "snapshot --background");
    free(t.trace);
    fc_decoded_image img;
    if (t.r.status == 0 && decode_png(out, &img)) {
        const uint8_t *corner = img.pixels;   /* the ball is in the middle: the corner is background */
        CHECK_MSG(img.width == 64 && img.height == 48 && corner[0] > 200 && corner[1] < 40 && corner[2] < 40,
                  "%ux%u, corner %u,%u,%u: not the red background", img.width, img.height, corner[0], corner[1],
                  corner[2]);
        fc_decoded_image_free(&img);
    }
}

static const char *const *legend_args(const test_env *env, char in[PATH_SIZE], char out[PATH_SIZE])
{
    static const char *args[16];
    const char *list[] = {"snapshot", scratch(env, "ballv.csv", in), "-o", scratch(env, "legend.png", out),
                          "--server", env->server, "--size", "160x120", "--color-by", "speed", "--range", "0:3",
                          "--legend", NULL};
    memcpy(args, list, sizeof list);
    return args;
}

static void test_legend_loads_images(test_env *env)
{
    char in[PATH_SIZE], out[PATH_SIZE];
    traced_run t;
    run_traced(env, NULL, legend_args(env, in, out), &t);
    CHECK_MSG(t.r.status == 0, "--legend: exit %d: %s", t.r.status, t.r.err);
    CHECK_MSG(strstr(t.r.out, "legend: columns ") != NULL, "stdout: %s", t.r.out);
    CHECK_MSG(loaded(&t, "fluidcast-image.so") && loaded(&t, "libOpenImageIO.so"), "--legend did not load them");
    CHECK_MSG(!loaded(&t, "fluidcast-video.so"), "--legend loaded the video module");   /* OpenImageIO needs libav itself */
    free(t.trace);
    fc_decoded_image img;
    if (t.r.status == 0 && decode_png(out, &img)) {
        CHECK(img.width == 160 && img.height == 120);
        fc_decoded_image_free(&img);
    }
}

static const char *const *video_args(const test_env *env, const char *name, char in[PATH_SIZE],
                                     char out[PATH_SIZE])
{
    static const char *args[16];
    const char *list[] = {"render", scratch(env, "ball.f32", in), in, "-o", scratch(env, name, out), "--server",
                          env->server, "--size", "64x48", NULL};
    memcpy(args, list, sizeof list);
    return args;
}

static void test_video_loads_libav(test_env *env)
{
    char in[PATH_SIZE], out[PATH_SIZE];
    traced_run t;
    run_traced(env, NULL, video_args(env, "two.mp4", in, out), &t);
    CHECK_MSG(t.r.status == 0, "render .mp4: exit %d: %s", t.r.status, t.r.err);
    CHECK_MSG(loaded(&t, "fluidcast-video.so") && loaded(&t, "libavformat.so"), "render .mp4 did not load them");
    CHECK_MSG(!loaded(&t, "libOpenImageIO.so"), "render .mp4 loaded OpenImageIO");
    CHECK_MSG(strstr(t.r.out, "libx264") || strstr(t.r.out, "mpeg4"), "stdout: %s", t.r.out);
    free(t.trace);
    size_t size = 0;
    uint8_t *mp4 = read_whole_file(out, &size);
    CHECK_MSG(mp4 && size > 200 && memcmp(mp4 + 4, "ftyp", 4) == 0, "%s: %zu bytes, not an MP4", out, size);
    free(mp4);
}

/* `view` is the module's: its help comes from there, with SDL2 loaded and nothing of the image module. */
static void test_view_loads_viewer(test_env *env)
{
    traced_run t;
    run_traced(env, NULL, (const char *const[]){"view", "--help", NULL}, &t);
    CHECK_MSG(t.r.status == 0, "view --help: exit %d: %s", t.r.status, t.r.err);
    CHECK_MSG(strstr(t.r.out, "usage: fluidcast view") != NULL, "stdout: %s", t.r.out);
    CHECK_MSG(loaded(&t, "fluidcast-view.so") && loaded(&t, "libSDL2"), "view did not load its module and SDL2");
    CHECK_MSG(!loaded(&t, "libOpenImageIO.so"), "view loaded OpenImageIO");
    free(t.trace);
}

/* An HDF5 file (tests/readers' h5py fixtures, FC_HDF5_FIXTURES; skipped without them): read through
 * fluidcast-hdf5.so and libhdf5, rendered; without the module, exit 3 naming it. */
static void test_hdf5_loads_its_reader(test_env *env)
{
    const char *fixtures = getenv("FC_HDF5_FIXTURES");
    char h5[PATH_SIZE], out[PATH_SIZE], dir[PATH_SIZE];
    snprintf(h5, sizeof h5, "%s/swift_f32.h5", fixtures ? fixtures : "");
    if (!fixtures || access(h5, R_OK) != 0) {
        printf("no HDF5 fixtures (h5py): the HDF5 module's part is skipped\n");
        return;
    }
    traced_run t;
    const char *args[] = {"snapshot", h5, "-o", scratch(env, "h5.png", out), "--server", env->server, "--size",
                          "64x48", "--up", "z", NULL};
    run_traced(env, NULL, args, &t);
    CHECK_MSG(t.r.status == 0, "snapshot of %s: exit %d: %s", h5, t.r.status, t.r.err);
    CHECK_MSG(loaded(&t, "fluidcast-hdf5.so") && loaded(&t, "libhdf5"), "an HDF5 file did not load its reader");
    CHECK_MSG(!loaded(&t, "libOpenImageIO.so") && !loaded(&t, "libSDL2"), "an HDF5 file loaded other modules");
    free(t.trace);
    fc_decoded_image img;
    if (t.r.status == 0 && decode_png(out, &img))
        fc_decoded_image_free(&img);
    unlink(out);
    run_traced(env, scratch(env, "no-modules", dir), args, &t);
    CHECK_CODE(t.r.status, 3);
    CHECK_MSG(strstr(t.r.err, "reading HDF5 needs the module fluidcast-hdf5.so") &&
                  strstr(t.r.err, "No such file or directory"),
              "stderr: %s", t.r.err);
    free(t.trace);
}

/* Without the modules: the commands that need them fail, naming the module and the loader's reason. */
static void test_missing_modules(test_env *env)
{
    char dir[PATH_SIZE], in[PATH_SIZE], out[PATH_SIZE];
    scratch(env, "no-modules", dir);
    traced_run t;
    run_traced(env, dir, (const char *const[]){"--version", NULL}, &t);
    CHECK_CODE(t.r.status, 0);
    free(t.trace);
    run_traced(env, dir,
               (const char *const[]){"snapshot", scratch(env, "ball.f32", in), "-o", scratch(env, "plain.png", out),
                                     "--server", env->server, "--size", "64x48", NULL},
               &t);
    CHECK_MSG(t.r.status == 0, "snapshot without modules: exit %d: %s", t.r.status, t.r.err);
    free(t.trace);
    fc_decoded_image img;
    if (t.r.status == 0 && decode_png(out, &img))
        fc_decoded_image_free(&img);

    run_traced(env, dir, legend_args(env, in, out), &t);
    CHECK_CODE(t.r.status, 6);
    CHECK_MSG(strstr(t.r.err, "--legend needs the module fluidcast-image.so") &&
                  strstr(t.r.err, "No such file or directory"),
              "stderr: %s", t.r.err);
    free(t.trace);
    run_traced(env, dir, video_args(env, "none.mp4", in, out), &t);
    CHECK_CODE(t.r.status, 6);
    CHECK_MSG(strstr(t.r.err, "video output needs the module fluidcast-video.so") &&
                  strstr(t.r.err, "No such file or directory"),
              "stderr: %s", t.r.err);
    CHECK_MSG(access(out, F_OK) != 0, "%s was created", out);
    free(t.trace);
    run_traced(env, dir, (const char *const[]){"view", "--help", NULL}, &t);
    CHECK_CODE(t.r.status, 2);
    CHECK_MSG(strstr(t.r.err, "fluidcast view needs the module fluidcast-view.so") &&
                  strstr(t.r.err, "No such file or directory"),
              "stderr: %s", t.r.err);
    free(t.trace);
}

/* Modules that are there but wrong: not an object file; an object without the interface. */
static void test_broken_modules(test_env *env)
{
    char dir[PATH_SIZE], in[PATH_SIZE], out[PATH_SIZE];
    scratch(env, "bad-modules", dir);
    traced_run t;
    run_traced(env, dir, video_args(env, "bad.mp4", in, out), &t);
    CHECK_CODE(t.r.status, 6);
    CHECK_MSG(strstr(t.r.err, "fluidcast-video.so, which cannot be loaded") &&
                  (strstr(t.r.err, "invalid ELF header") || strstr(t.r.err, "file too short")),
              "stderr: %s", t.r.err);
    free(t.trace);
    run_traced(env, dir, legend_args(env, in, out), &t);
    CHECK_CODE(t.r.status, 6);
    CHECK_MSG(strstr(t.r.err, "fluidcast-image.so, which is broken (fc_image_module_v1)") &&
                  strstr(t.r.err, "undefined symbol"),
              "stderr: %s", t.r.err);
    free(t.trace);
}

static void remove_scratch(const test_env *env)
{
    static const char *const names[] = {"ball.f32", "ballv.csv", "red.png", "bg.png", "legend.png", "two.mp4",
                                        "plain.png", "bad-modules/fluidcast-video.so",
                                        "bad-modules/fluidcast-image.so", "none.mp4", "bad.mp4"};
    char path[PATH_SIZE];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        unlink(scratch(env, names[i], path));
    rmdir(scratch(env, "no-modules", path));
    rmdir(scratch(env, "bad-modules", path));
    rmdir(env->dir);
}

int main(void)
{
    test_env env = {.traces = 0};
    strcpy(env.dir, "/tmp/fluidcast-modules-XXXXXX");
    if (!mkdtemp(env.dir) || !write_fixtures(&env)) {
        fprintf(stderr, "cannot set up the scratch directory\n");
        return 1;
    }
    test_version(&env);
    test_view_loads_viewer(&env);
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        remove_scratch(&env);
        return 1;
    }
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_snapshot_is_light(&env);
    test_legend_loads_images(&env);
    test_video_loads_libav(&env);
    test_hdf5_loads_its_reader(&env);
    test_missing_modules(&env);
    test_broken_modules(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    remove_scratch(&env);
    return test_result();
}
