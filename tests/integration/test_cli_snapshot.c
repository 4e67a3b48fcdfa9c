/* test_cli_snapshot.c — the real fluidcast binary against the real fluidcastd
 * (and, for failures after connecting, a fake server): the images it writes
 * (size, magic bytes, fluid where the ball projects and background elsewhere,
 * the analytic depth of the ball's front), what it prints, and every exit code. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fake_server.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "support/tinted_look.h"
#include "test_ball.h"
#include "test_util.h"

#define LIVE_PATHS 8

/* Storage for the paths scratch() hands out; the last LIVE_PATHS stay valid. */
typedef struct path_ring {
    char slots[LIVE_PATHS][128];
    unsigned next;
} path_ring;

typedef struct test_env {
    char dir[64];              /* scratch directory: particle files, images, captures */
    char server[32];           /* HOST:PORT of the daemon */
    path_ring *paths;
} test_env;

static const char *scratch(test_env *env, const char *name)
{
    char *p = env->paths->slots[env->paths->next++ % LIVE_PATHS];
    snprintf(p, sizeof env->paths->slots[0], "%s/%s", env->dir, name);
    return p;
}

static void run(test_env *env, cli_result *r, const char *const *args)
{
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
}

static bool write_scene_files(test_env *env)
{
    fc_frame ball = { 0 }, corners = { 0 };
    bool ok = test_ball_frame(&ball, NULL) == FC_OK && test_ball_box_corners(&corners, NULL) == FC_OK &&
              test_write_f32(&ball, scratch(env, "ball.f32")) && test_write_ply(&ball, scratch(env, "ball.ply")) &&
              test_write_f32(&corners, scratch(env, "corners.f32"));
    fc_frame_free(&ball);
    fc_frame_free(&corners);
    FILE *broken = fopen(scratch(env, "broken.ply"), "w");
    ok = ok && broken && fputs("ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nend_header\n1\n2\n",
                               broken) >= 0;
    if (broken)
        ok = fclose(broken) == 0 && ok;
    return ok;
}

/* ---- images ---- */

typedef struct rgb {
    int c[3];
} rgb;

static rgb pixel_at(const fc_decoded_image *img, uint32_t x, uint32_t y)
{
    const uint8_t *p = (const uint8_t *)img->pixels + ((size_t)y * img->width + x) * img->channels;
    rgb out = { { p[0], p[1], p[2] } };
    return out;
}

static int colour_distance(rgb a, rgb b)
{
    return abs(a.c[0] - b.c[0]) + abs(a.c[1] - b.c[1]) + abs(a.c[2] - b.c[2]);
}

static bool decode_file(const char *path, const char *extension, int as_float, fc_decoded_image *out)
{
    size_t size;
    uint8_t *data = read_whole_file(path, &size);
    fc_error err;
    fc_code code = data ? fc_decode_image(data, size, extension, as_float, out, &err) : FC_ERR_IO;
    CHECK_MSG(code == FC_OK, "decoding %s: %s", path, data ? err.message : "unreadable");
    free(data);
    return code == FC_OK;
}

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void check_magic(const char *path, const uint8_t *magic, size_t n)
{
    size_t size;
    uint8_t *data = read_whole_file(path, &size);
    CHECK_MSG(data && size > n && memcmp(data, magic, n) == 0, "%s lacks its format's magic bytes", path);
    free(data);
}

/* The luma component's sampling factors (H << 4 | V) in the file's first SOF0
 * frame header, read from its bytes; 0 when there is none. 0x11: 4:4:4, 0x22: 4:2:0. */
static int jpeg_luma_sampling(const char *path)
{
    size_t size;
    uint8_t *data = read_whole_file(path, &size);
    int factors = 0;
    size_t at = 2;
    while (data && at + 4 <= size && data[at] == 0xFF) {
        if (data[at + 1] == 0xC0 && at + 4 + 8 <= size) {
            factors = data[at + 4 + 7];   /* precision, height, width, components, then component 1: id, HV */
            break;
        }
        if (data[at + 1] == 0xDA)
            break;
        at += 2 + ((size_t)data[at + 2] << 8 | data[at + 3]);
    }
    free(data);
    return factors;
}

/* ---- the tests ---- */

static void test_help_and_version(test_env *env)
{
    cli_result r;
    run(env, &r, (const char *const[]){ "--version", NULL });
    CHECK_CODE(r.status, 0);
    CHECK(strncmp(r.out, "fluidcast 0.", 12) == 0);
    run(env, &r, (const char *const[]){ "--help", NULL });
    CHECK_CODE(r.status, 0);
    CHECK(strstr(r.out, "snapshot") && strstr(r.out, "7  protocol or connection failure"));
    run(env, &r, (const char *const[]){ "snapshot", "--help", NULL });
    CHECK_CODE(r.status, 0);
    CHECK(strstr(r.out, "--radius R") && strstr(r.out, "estimated from") && strstr(r.out, "particle spacing"));
}

/* The explicit camera on the -y axis: the ball (radius 0.55 with its spheres)
 * spans about 23 px around the centre of a 160x120 image. The box-corner frame
 * has the same bounds, so the same floor and sky, and nothing at the pixels sampled. */
static void test_png_shows_ball_over_background(test_env *env)
{
    const char *common[] = { "--server", env->server, "--size", "160x120", "--eye", "0,-4,0", "--target", "0,0,0",
                             "--radius", "0.05", "--absorption", TINTED_LOOK_ABSORPTION };
    cli_result r;
    const char *ball_args[18] = { "snapshot", scratch(env, "ball.f32"), "-o", scratch(env, "ball.png") };
    const char *empty_args[18] = { "snapshot", scratch(env, "corners.f32"), "-o", scratch(env, "empty.png") };
    memcpy(ball_args + 4, common, sizeof common);
    memcpy(empty_args + 4, common, sizeof common);
    run(env, &r, ball_args);
    CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);
    /* Two lines: what was written, then the up direction it chose without
     * --up (a ball has no floor to guess from). */
    CHECK_MSG(strncmp(r.out, "wrote ", 6) == 0 && strstr(r.out, "160x120 PNG") &&
                  strstr(r.out, "radius 0.05\nup +z (default: no floor among the particles; --up to override)\n"),
              "stdout: %s", r.out);
    const char *first_end = strchr(r.out, '\n');
    CHECK(first_end && strchr(first_end + 1, '\n') == r.out + strlen(r.out) - 1);
    run(env, &r, empty_args);
    CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);

    size_t size;
    uint8_t *png = read_whole_file(scratch(env, "ball.png"), &size);
    static const uint8_t signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
    CHECK(png && size > 24 && memcmp(png, signature, 8) == 0 && memcmp(png + 12, "IHDR", 4) == 0);
    if (png && size > 24)
        CHECK(be32(png + 16) == 160 && be32(png + 20) == 120);
    free(png);

    fc_decoded_image ball, empty;
    if (!decode_file(scratch(env, "ball.png"), "png", 0, &ball))
        return;
    if (decode_file(scratch(env, "empty.png"), "png", 0, &empty)) {
        CHECK(ball.width == 160 && ball.height == 120 && ball.channels >= 3);
        CHECK(empty.width == 160 && empty.height == 120);
        const uint32_t cx = 80, cy = 60;
        CHECK_MSG(colour_distance(pixel_at(&ball, cx, cy), pixel_at(&ball, 0, 0)) > 30,
                  "the centre looks like the corner's background");
        for (int d = -8; d <= 8; d += 4)
            CHECK_MSG(colour_distance(pixel_at(&ball, cx + d, cy + d), pixel_at(&empty, cx + d, cy + d)) > 30,
                      "no fluid at offset %d", d);
        const uint32_t outside[][2] = { { cx - 45, cy }, { cx + 45, cy }, { cx, cy - 45 }, { cx, cy + 45 }, { 0, 0 },
                                        { 159, 119 } };
        for (size_t i = 0; i < sizeof outside / sizeof outside[0]; i++)
            CHECK_MSG(colour_distance(pixel_at(&ball, outside[i][0], outside[i][1]),
                                      pixel_at(&empty, outside[i][0], outside[i][1])) <= 6,
                      "pixel %u,%u is not background", outside[i][0], outside[i][1]);
        fc_decoded_image_free(&empty);
    }
    fc_decoded_image_free(&ball);
}

/* Without --eye and --radius: the camera frames the box, so the ball is at the
 * centre, and the radius is 0.9 x the lattice spacing (every nearest
 * neighbour is exactly one spacing away). */
static void test_ply_auto_camera_and_radius(test_env *env)
{
    cli_result r;
    run(env, &r, (const char *const[]){ "snapshot", scratch(env, "ball.ply"), "-o", scratch(env, "auto.png"),
                                        "--server", env->server, "--size", "160x120", NULL });
    CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);
    CHECK_MSG(strstr(r.out, "radius 0.05625 (estimated from particle spacing)") != NULL, "stdout: %s", r.out);
    fc_decoded_image img;
    if (!decode_file(scratch(env, "auto.png"), "png", 0, &img))
        return;
    CHECK(img.width == 160 && img.height == 120);
    CHECK(colour_distance(pixel_at(&img, 80, 60), pixel_at(&img, 0, 0)) > 30);
    fc_decoded_image_free(&img);
}

static void test_jpeg_and_exr_magic(test_env *env)
{
    cli_result r;
    run(env, &r, (const char *const[]){ "snapshot", scratch(env, "ball.f32"), "-o", scratch(env, "ball.jpg"),
                                        "--server", env->server, "--size", "64x48", "--quality", "80", NULL });
    CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);
    check_magic(scratch(env, "ball.jpg"), (const uint8_t[]){ 0xff, 0xd8, 0xff }, 3);
    CHECK_MSG(jpeg_luma_sampling(scratch(env, "ball.jpg")) == 0x11, "default JPEG is not 4:4:4");
    /* Settings key 32 through the daemon: the file the server encoded says 4:2:0. */
    run(env, &r, (const char *const[]){ "snapshot", scratch(env, "ball.f32"), "-o", scratch(env, "ball420.jpg"),
                                        "--server", env->server, "--size", "64x48", "--jpeg-subsampling", "420",
                                        NULL });
    CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);
    CHECK_MSG(jpeg_luma_sampling(scratch(env, "ball420.jpg")) == 0x22, "--jpeg-subsampling 420 is not 4:2:0");
    run(env, &r, (const char *const[]){ "snapshot", scratch(env, "ball.f32"), "-o", scratch(env, "ball.exr"),
                                        "--server", env->server, "--size", "64x48", "--smoothing", "none", NULL });
    CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);
    check_magic(scratch(env, "ball.exr"), (const uint8_t[]){ 0x76, 0x2f, 0x31, 0x01 }, 4);
}

/* Odd size: the centre pixel lies on the view axis, which meets the sphere of
 * the particle at (0,-0.5,0) at distance 4 - 0.5 - 0.05 from the eye. */
static void test_depth_aov(test_env *env)
{
    cli_result r;
    run(env, &r, (const char *const[]){ "snapshot", scratch(env, "ball.f32"), "-o", scratch(env, "depth.exr"),
                                        "--server", env->server, "--size", "161x121", "--eye", "0,-4,0", "--target",
                                        "0,0,0", "--radius", "0.05", "--aov", "depth", NULL });
    CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);
    fc_decoded_image img;
    if (!decode_file(scratch(env, "depth.exr"), "exr", 1, &img))
        return;
    CHECK(img.width == 161 && img.height == 121);
    CHECK_MSG(img.channels == 1, "%u channels", img.channels);
    const float *depth = img.pixels;
    CHECK_NEAR(depth[60 * 161 + 80], BALL_FRONT_DEPTH, 0.02 * BALL_FRONT_DEPTH);
    CHECK(depth[0] == 0.0f);
    fc_decoded_image_free(&img);
}

/* A PLY with a radius per particle (0.2 and 0.5, 4 units in front of the
 * eye): the depth at each centre is 4 - r_i, the CLI says it used the file's
 * radii; --radius 0.3 overrides both. The image's x follows world x here. */
static void test_radius_from_the_file(test_env *env)
{
    FILE *f = fopen(scratch(env, "radii.ply"), "w");
    CHECK(f && fputs("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                     "property float z\nproperty float radius\nend_header\n-0.6 0 0 0.2\n0.6 0 0 0.5\n",
                     f) >= 0);
    if (f)
        fclose(f);
    const double focal = 0.5 * 81 / tan(20.0 * 3.14159265358979323846 / 180.0); /* pixels per x / depth */
    const int columns[2] = { (int)(80 - 0.6 * focal / 4 + 0.5), (int)(80 + 0.6 * focal / 4 + 0.5) };
    const float radii[2] = { 0.2f, 0.5f };
    for (int override = 0; override < 2; override++) {
        cli_result r;
        run(env, &r, (const char *const[]){ "snapshot", scratch(env, "radii.ply"), "-o", scratch(env, "radii.exr"),
                                            "--server", env->server, "--size", "161x81", "--eye", "0,-4,0",
                                            "--target", "0,0,0", "--aov", "depth", override ? "--radius" : NULL,
                                            "0.3", NULL });
        CHECK_MSG(r.status == 0, "exit %d: %s", r.status, r.err);
        bool says = strstr(r.out, "radius: per-particle radii from the file (median 0.5") != NULL;
        CHECK_MSG(says != (override == 1), "stdout: %s", r.out);
        fc_decoded_image img;
        if (!decode_file(scratch(env, "radii.exr"), "exr", 1, &img))
            return;
        const float *depth = img.pixels;
        for (int i = 0; i < 2 && img.width == 161 && img.height == 81; i++) {
            double expected = 4.0 - (override ? 0.3 : radii[i]);
            CHECK_MSG(fabs(depth[40 * 161 + columns[i]] - expected) < 0.01, "particle %d: depth %g, expected %g", i,
                      (double)depth[40 * 161 + columns[i]], expected);
        }
        fc_decoded_image_free(&img);
    }
}

static void expect_exit(test_env *env, int expected, const char *const *args)
{
    cli_result r;
    run(env, &r, args);
    CHECK_MSG(r.status == expected, "%s %s ...: exit %d, expected %d; stderr: %s", args[0], args[1], r.status,
              expected, r.err);
    CHECK_MSG(strncmp(r.err, "fluidcast: ", 11) == 0, "stderr: %s", r.err);
    CHECK_MSG(r.out[0] == '\0', "stdout: %s", r.out);
}

static void test_usage_errors(test_env *env)
{
    const char *ball = scratch(env, "ball.f32"), *png = scratch(env, "never.png");
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--bogus", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--size", "0x5", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--aov", "depth", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", scratch(env, "x.gif"), NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--eye", "1,2,3", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--fov", "180", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--server", "localhost:http", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--jpeg-subsampling", "420", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", scratch(env, "never.jpg"),
                                               "--jpeg-subsampling", "422", NULL });
    expect_exit(env, 2, (const char *const[]){ "frobnicate", NULL });
    CHECK(access(png, F_OK) != 0);
}

static void test_input_server_and_output_errors(test_env *env)
{
    char unused_server[32];
    snprintf(unused_server, sizeof unused_server, "127.0.0.1:%u", (unsigned)fake_unused_port());
    const char *ball = scratch(env, "ball.f32"), *png = scratch(env, "never.png");
    expect_exit(env, 3, (const char *const[]){ "snapshot", scratch(env, "missing.f32"), "-o", png, "--server",
                                               env->server, NULL });
    expect_exit(env, 3, (const char *const[]){ "snapshot", scratch(env, "broken.ply"), "-o", png, "--server",
                                               env->server, NULL });
    expect_exit(env, 4, (const char *const[]){ "snapshot", ball, "-o", png, "--server", unused_server, NULL });
    /* The daemon runs with --max-image 256x256. */
    expect_exit(env, 5, (const char *const[]){ "snapshot", ball, "-o", png, "--server", env->server, "--size",
                                               "512x200", NULL });
    expect_exit(env, 6, (const char *const[]){ "snapshot", ball, "-o", scratch(env, "no/such/dir.png"),
                                               "--server", env->server, "--size", "32x24", NULL });
    CHECK(access(png, F_OK) != 0);
}

/* A fake server's first step: the client's HELLO. */
static void expect_hello(fake_connection *conn)
{
    fc_test_message m = { 0 };
    if (!fake_expect(conn, FC_MSG_HELLO, &m))
        conn->failures++;
    fc_test_message_free(&m);
}

/* A fake server running `script`, its "127.0.0.1:PORT" in address; NULL (a failed check) when none starts. */
static fake_server *start_fake(fake_script script, char address[32])
{
    fake_server *fake = fake_server_start(script);
    CHECK(fake != NULL);
    if (fake)
        snprintf(address, 32, "127.0.0.1:%u", (unsigned)fake_server_port(fake));
    return fake;
}

static void script_garbage_welcome(fake_connection *conn)
{
    expect_hello(conn);
    static const char garbage[] = "SSH-2.0-OpenSSH_9.2\r\n";
    fc_test_send(conn->fd, garbage, sizeof garbage - 1, NULL);
}

static void test_protocol_failure(test_env *env)
{
    char address[32];
    fake_server *fake = start_fake(script_garbage_welcome, address);
    if (!fake)
        return;
    expect_exit(env, 7, (const char *const[]){ "snapshot", scratch(env, "ball.f32"), "-o", scratch(env, "never.png"),
                                               "--server", address, NULL });
    CHECK_CODE(fake_server_finish(fake), 0);
}

/* A server that takes the HELLO and never answers, until the client hangs up. */
static void script_silent_after_hello(fake_connection *conn)
{
    expect_hello(conn);
    char byte;
    while (read(conn->fd, &byte, 1) > 0) {
    }
}

static double elapsed_ms(const struct timespec *since)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (now.tv_sec - since->tv_sec) * 1e3 + (now.tv_nsec - since->tv_nsec) / 1e6;
}

/* --connect-timeout bounds the wait for the WELCOME (the library's default is
 * 10 s): against a server that never answers, the CLI gives up after about
 * the half second asked for, saying it timed out; a value that is no number of
 * seconds in (0, 3600] is a usage error, before any connection. */
static void test_connect_timeout(test_env *env)
{
    const char *ball = scratch(env, "ball.f32"), *png = scratch(env, "never.png");
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--connect-timeout", "0", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--connect-timeout=-1", NULL });
    expect_exit(env, 2, (const char *const[]){ "snapshot", ball, "-o", png, "--connect-timeout", "5000", NULL });
    expect_exit(env, 2, (const char *const[]){ "info", "--connect-timeout", "soon", NULL });
    expect_exit(env, 2, (const char *const[]){ "info", "--connect-timeout", NULL });

    char address[32];
    fake_server *fake = start_fake(script_silent_after_hello, address);
    if (!fake)
        return;
    struct timespec start;
    clock_gettime(CLOCK_MONOTONIC, &start);
    cli_result r;
    run(env, &r, (const char *const[]){ "snapshot", ball, "-o", png, "--server", address, "--connect-timeout",
                                        "0.5", NULL });
    double ms = elapsed_ms(&start);
    CHECK_MSG(r.status == 7 && strstr(r.err, "timed out") != NULL, "exit %d; stderr: %s", r.status, r.err);
    /* Below the default's 10 s with room for a slow start (ASan, a loaded machine):
     * the half second asked for was used, not the default. */
    CHECK_MSG(ms >= 400.0 && ms < 9000.0, "gave up after %.0f ms, asked 500 (the default is 10000)", ms);
    CHECK(access(png, F_OK) != 0);
    CHECK_CODE(fake_server_finish(fake), 0);
}

static void remove_scratch(test_env *env)
{
    const char *names[] = { "ball.f32", "ball.ply", "corners.f32", "broken.ply", "ball.png", "empty.png",
                            "auto.png", "ball.jpg", "ball420.jpg", "ball.exr", "depth.exr", "radii.ply",
                            "radii.exr" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        unlink(scratch(env, names[i]));
    rmdir(env->dir);
}

int main(void)
{
    path_ring paths = { .next = 0 };
    test_env env = { .paths = &paths };
    strcpy(env.dir, "/tmp/fluidcast-cli-test-XXXXXX");
    if (!mkdtemp(env.dir) || !write_scene_files(&env)) {
        fprintf(stderr, "cannot set up the scratch directory\n");
        return 1;
    }
    test_help_and_version(&env);
    test_usage_errors(&env);

    test_protocol_failure(&env);
    test_connect_timeout(&env);

    fc_test_daemon daemon;
    fc_error err;
    static const char *const daemon_args[] = { "--max-image", "256x256", NULL };
    if (fc_test_daemon_start(&daemon, daemon_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        remove_scratch(&env);
        return 1;
    }
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_png_shows_ball_over_background(&env);
    test_ply_auto_camera_and_radius(&env);
    test_jpeg_and_exr_magic(&env);
    test_depth_aov(&env);
    test_radius_from_the_file(&env);
    test_input_server_and_output_errors(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    remove_scratch(&env);
    return test_result();
}
