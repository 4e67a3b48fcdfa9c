/* test_cli_up.c — the up direction of the fluidcast CLI, against the real
 * fluidcastd: without --up the axis is guessed from the particles, printed,
 * and the camera turns with it (a pool with a tall jet stored y-up renders
 * like the same pool stored z-up, with the jet rising straight up the
 * picture); --up x|y|z|-x|-y|-z equals the vector it abbreviates; a shape with
 * no floor keeps +z and says "default"; an explicit view along the guessed
 * axis falls back to +z; bad --up values are usage errors for snapshot and
 * stream; stream prints its guess too. The pictures are thickness AOVs, so
 * "fluid here" is exact: thickness > 0. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "aov_coverage.h"
#include "cli_runner.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "support/daemon_process.h"
#include "test_ball.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 64

typedef struct test_env {
    char dir[64];
    char server[32];
} test_env;

static const char *path_in(const test_env *env, const char *name, char *buf, size_t size)
{
    snprintf(buf, size, "%s/%s", env->dir, name);
    return buf;
}

/* ---- particle files ---- */

/* A 0.6 x 0.6 x 0.1 pool resting on z = 0 (jittered lattice, spacing 0.025)
 * and a jet: one column of particles 0.02 apart rising to z = 0.9 from the
 * pool's centre. (x, y, z) -> (x, z, -y) stores the same fluid y-up. */
static fc_code pool_with_jet(fc_frame *f, bool y_up, fc_error *err)
{
    const int n = 24, layers = 4, jet = 40;
    const double h = 0.025;
    fc_code code = fc_frame_alloc(f, (uint64_t)n * n * layers + jet, 0, err);
    if (code != FC_OK)
        return code;
    uint64_t i = 0;
    uint32_t seed = 12345;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++)
            for (int c = 0; c < layers; c++) {
                seed = seed * 1664525u + 1013904223u;
                double wobble = ((seed >> 8) / 16777216.0 - 0.5) * 0.2 * h;
                float *p = f->positions + 3 * i++;
                p[0] = (float)((a + 0.5) * h + wobble);
                p[1] = (float)((b + 0.5) * h - wobble);
                p[2] = (float)((c + 0.5) * h + 0.5 * wobble);
            }
    for (int j = 0; j < jet; j++) {
        float *p = f->positions + 3 * i++;
        p[0] = p[1] = (float)(0.5 * n * h);
        p[2] = (float)(layers * h + 0.02 * (j + 1));
    }
    if (y_up)
        for (uint64_t k = 0; k < f->count; k++) {
            float *p = f->positions + 3 * k, y = p[1];
            p[1] = p[2];
            p[2] = -y;
        }
    return FC_OK;
}

static bool write_files(const test_env *env)
{
    char buf[128];
    fc_frame z_up = { 0 }, y_up = { 0 }, ball = { 0 };
    bool ok = pool_with_jet(&z_up, false, NULL) == FC_OK && pool_with_jet(&y_up, true, NULL) == FC_OK &&
              test_ball_frame(&ball, NULL) == FC_OK && test_write_f32(&z_up, path_in(env, "pool_z.f32", buf, sizeof buf)) &&
              test_write_f32(&y_up, path_in(env, "pool_y.f32", buf, sizeof buf)) &&
              test_write_f32(&ball, path_in(env, "ball.f32", buf, sizeof buf));
    fc_frame_free(&z_up);
    fc_frame_free(&y_up);
    fc_frame_free(&ball);
    return ok;
}

/* ---- running the CLI ---- */

#define MAX_ARGS 24

/* `fluidcast snapshot INPUT -o OUTPUT --server S --size WxH --aov thickness
 * --radius 0.02 [extra...]`; extra is NULL-terminated. */
static void snapshot(const test_env *env, const char *input, const char *output, const char *const *extra,
                     cli_result *r)
{
    char in[128], out[128];
    const char *args[MAX_ARGS] = { "snapshot", path_in(env, input, in, sizeof in), "-o",
                                   path_in(env, output, out, sizeof out), "--server", env->server, "--size", "96x64",
                                   "--aov", "thickness", "--radius", "0.02" };
    int n = 12;
    for (int i = 0; extra && extra[i] && n < MAX_ARGS - 1; i++)
        args[n++] = extra[i];
    args[n] = NULL;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
    CHECK_MSG(r->status == 0, "snapshot %s: exit %d: %s", input, r->status, r->err);
}

/* Where the thickness AOV is > 0: WIDTH x HEIGHT flags, or NULL. */
static bool *coverage(const test_env *env, const char *name)
{
    char path[128];
    bool *covered = aov_coverage(path_in(env, name, path, sizeof path), WIDTH, HEIGHT);
    CHECK_MSG(covered, "decoding %s", name);
    return covered;
}

/* Pixels covered in one picture and not the other. */
static int differing(const bool *a, const bool *b)
{
    return coverage_difference(a, b, WIDTH * HEIGHT);
}

static int covered_count(const bool *c)
{
    int n = 0;
    for (int i = 0; i < WIDTH * HEIGHT; i++)
        n += c[i];
    return n;
}

/* Upright: the jet is the only fluid in the top quarter of the picture, and
 * rises there as a near-vertical column within the middle sixth of the width;
 * the pool fills the lower half. */
static void check_upright(const bool *c, const char *what)
{
    int top = 0, top_off_centre = 0, lower = 0;
    for (int y = 0; y < HEIGHT; y++)
        for (int x = 0; x < WIDTH; x++) {
            if (!c[y * WIDTH + x])
                continue;
            if (y < HEIGHT / 4) {
                top++;
                top_off_centre += abs(2 * x - WIDTH) > WIDTH / 6;
            }
            lower += y >= HEIGHT / 2;
        }
    CHECK_MSG(top > 0 && top_off_centre == 0, "%s: %d fluid pixels in the top quarter, %d off centre", what, top,
              top_off_centre);
    CHECK_MSG(lower > covered_count(c) / 2, "%s: %d of %d fluid pixels in the lower half", what, lower,
              covered_count(c));
}

/* ---- tests ---- */

/* y-up data without --up: "+y" printed, the picture upright and the same as
 * with --up y (the camera used is the one printed) and as the z-up data
 * guessed +z; with --up z (the old default) it is a different picture. */
static void test_guess_turns_the_camera(const test_env *env)
{
    cli_result r;
    snapshot(env, "pool_y.f32", "guess_y.exr", NULL, &r);
    CHECK_MSG(strstr(r.out, "\nup +y (guessed from the particles; --up to override)\n") != NULL, "stdout: %s", r.out);
    snapshot(env, "pool_y.f32", "given_y.exr", (const char *const[]){ "--up", "y", NULL }, &r);
    CHECK_MSG(strstr(r.out, "\nup ") == NULL, "--up given, yet: %s", r.out);
    snapshot(env, "pool_z.f32", "guess_z.exr", NULL, &r);
    CHECK_MSG(strstr(r.out, "\nup +z (guessed from the particles; --up to override)\n") != NULL, "stdout: %s", r.out);
    snapshot(env, "pool_y.f32", "given_z.exr", (const char *const[]){ "--up", "0,0,1", NULL }, &r);

    bool *guess_y = coverage(env, "guess_y.exr"), *given_y = coverage(env, "given_y.exr");
    bool *guess_z = coverage(env, "guess_z.exr"), *given_z = coverage(env, "given_z.exr");
    if (guess_y && given_y && guess_z && given_z) {
        CHECK_MSG(covered_count(guess_y) > 200, "%d fluid pixels", covered_count(guess_y));
        CHECK_MSG(differing(guess_y, given_y) == 0, "%d pixels differ",
                  differing(guess_y, given_y));
        /* Rotating the data and the camera alike changes only float rounding. */
        CHECK_MSG(differing(guess_y, guess_z) <= WIDTH * HEIGHT / 100, "%d pixels differ",
                  differing(guess_y, guess_z));
        CHECK_MSG(differing(guess_y, given_z) > WIDTH * HEIGHT / 20, "only %d pixels differ",
                  differing(guess_y, given_z));
        check_upright(guess_y, "y-up data, guessed");
        check_upright(guess_z, "z-up data, guessed");
    }
    free(guess_y);
    free(given_y);
    free(guess_z);
    free(given_z);
}

/* Each letter is the unit vector it names: --up -y and --up 0,-1,0 give the
 * same picture, and it is not the --up y one. */
static void test_shorthand_equals_vector(const test_env *env)
{
    cli_result r;
    snapshot(env, "pool_y.f32", "minus_y_letter.exr", (const char *const[]){ "--up", "-y", NULL }, &r);
    snapshot(env, "pool_y.f32", "minus_y_vector.exr", (const char *const[]){ "--up=0,-1,0", NULL }, &r);
    snapshot(env, "pool_y.f32", "plus_x_letter.exr", (const char *const[]){ "--up", "+x", NULL }, &r);
    snapshot(env, "pool_y.f32", "plus_x_vector.exr", (const char *const[]){ "--up", "1,0,0", NULL }, &r);
    bool *letter = coverage(env, "minus_y_letter.exr"), *vector = coverage(env, "minus_y_vector.exr");
    bool *x_letter = coverage(env, "plus_x_letter.exr"), *x_vector = coverage(env, "plus_x_vector.exr");
    bool *plus = coverage(env, "given_y.exr");
    if (letter && vector && x_letter && x_vector && plus) {
        CHECK(covered_count(letter) > 200);
        CHECK(differing(letter, vector) == 0);
        CHECK(differing(x_letter, x_vector) == 0);
        CHECK_MSG(differing(letter, plus) > WIDTH * HEIGHT / 20, "-y looks like +y");
    }
    free(letter);
    free(vector);
    free(x_letter);
    free(x_vector);
    free(plus);
}

/* A ball has no floor: +z, called a default. */
static void test_no_floor_keeps_z(const test_env *env)
{
    cli_result r;
    snapshot(env, "ball.f32", "ball.exr", NULL, &r);
    CHECK_MSG(strstr(r.out, "\nup +z (default: no floor among the particles; --up to override)\n") != NULL,
              "stdout: %s", r.out);
}

/* An explicit view straight down the guessed +y cannot be oriented by it: +z
 * stands in, and the note says why. */
static void test_view_along_guess(const test_env *env)
{
    cli_result r;
    snapshot(env, "pool_y.f32", "top.exr",
             (const char *const[]){ "--eye", "0.3,3,-0.3", "--target", "0.3,0,-0.3", NULL }, &r);
    CHECK_MSG(strstr(r.out, "\nup +z (the view looks along +y; --up to override)\n") != NULL, "stdout: %s", r.out);
    bool *top = coverage(env, "top.exr");
    if (top)   /* from above, the pool is a square in the middle of the picture */
        CHECK_MSG(top[(HEIGHT / 2) * WIDTH + WIDTH / 2] && !top[0], "top view: centre %d corner %d",
                  top[(HEIGHT / 2) * WIDTH + WIDTH / 2], top[0]);
    free(top);
}

static void expect_usage_error(const test_env *env, const char *const *args)
{
    cli_result r;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, &r);
    CHECK_MSG(r.status == 2, "%s ... %s: exit %d", args[0], args[3], r.status);
    CHECK_MSG(strstr(r.err, "fluidcast: --up needs x, y, z, -x, -y, -z or X,Y,Z") != NULL, "stderr: %s", r.err);
    CHECK_MSG(r.out[0] == '\0', "stdout: %s", r.out);
}

static void test_bad_values(const test_env *env)
{
    char in[128];
    const char *pool = path_in(env, "pool_y.f32", in, sizeof in);
    const char *bad[] = { "w", "xy", "+", "-", "", "X", "1,2", "1,2,3,4", "y,0,0", "nan,0,1" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        expect_usage_error(env, (const char *const[]){ "snapshot", pool, "--up", bad[i], "-o", "never.png", NULL });
        expect_usage_error(env, (const char *const[]){ "stream", pool, "--up", bad[i], NULL });
    }
}

/* stream frames its first file: the guess is printed before the frame lines,
 * and --up silences it. */
static void test_stream_prints_guess(const test_env *env)
{
    char in[128], out_dir[128];
    const char *pool = path_in(env, "pool_y.f32", in, sizeof in);
    path_in(env, "streamed", out_dir, sizeof out_dir);
    cli_result r;
    cli_run(FLUIDCAST_CLI_PATH, env->dir,
            (const char *const[]){ "stream", pool, pool, "--server", env->server, "--size", "32x24", "--out-dir",
                                   out_dir, NULL },
            &r);
    CHECK_MSG(r.status == 0, "stream: exit %d: %s", r.status, r.err);
    CHECK_MSG(strncmp(r.out, "up +y (guessed from the particles; --up to override)\nframe 1/2 ", 60) == 0,
              "stdout: %s", r.out);
    cli_run(FLUIDCAST_CLI_PATH, env->dir,
            (const char *const[]){ "stream", pool, "--server", env->server, "--size", "32x24", "--up", "-z", NULL },
            &r);
    CHECK_MSG(r.status == 0 && strncmp(r.out, "frame 1/1 ", 10) == 0, "stream --up -z: exit %d\n%s%s", r.status,
              r.out, r.err);
    for (int i = 1; i <= 2; i++) {
        char frame[160];
        snprintf(frame, sizeof frame, "%s/frame_%06d.png", out_dir, i);
        CHECK_MSG(unlink(frame) == 0, "%s", frame);
    }
    rmdir(out_dir);
}

static void remove_scratch(const test_env *env)
{
    const char *names[] = { "pool_z.f32", "pool_y.f32", "ball.f32", "guess_y.exr", "given_y.exr", "guess_z.exr",
                            "given_z.exr", "minus_y_letter.exr", "minus_y_vector.exr", "plus_x_letter.exr",
                            "plus_x_vector.exr", "ball.exr", "top.exr", "cli.stdout", "cli.stderr" };
    char path[128];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        unlink(path_in(env, names[i], path, sizeof path));
    rmdir(env->dir);
}

int main(void)
{
    test_env env = { .dir = "/tmp/fluidcast-cli-up-XXXXXX" };
    if (!mkdtemp(env.dir) || !write_files(&env)) {
        fprintf(stderr, "cannot set up the scratch directory\n");
        return 1;
    }
    test_bad_values(&env);
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        remove_scratch(&env);
        return 1;
    }
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_guess_turns_the_camera(&env);
    test_shorthand_equals_vector(&env);
    test_no_floor_keeps_z(&env);
    test_view_along_guess(&env);
    test_stream_prints_guess(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    remove_scratch(&env);
    return test_result();
}
