/* test_cli_framing.c — the auto camera of the fluidcast CLI frames the fluid,
 * not its farthest droplet (client/cli/framing_bounds.h), against the real
 * fluidcastd: a 1 x 1 x 0.15 pool with one droplet at z = 2.1 is framed as the
 * pool alone is (and the pool spans at least 40% of a 16:9 picture's width,
 * where the droplet's bounding box left it under 30%), and says it left the
 * droplet out; a sequence whose middle frame alone has the droplet keeps the
 * pool's camera in every frame; a compact fluid (a ball) is framed whole, as
 * before, with nothing said. The pictures are thickness AOVs, so "fluid here"
 * is exact: thickness > 0. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "aov_coverage.h"
#include "cli_runner.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "support/daemon_process.h"
#include "test_ball.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 54
#define PATH_CAP 160

typedef struct test_env {
    char dir[64];
    char server[32];
} test_env;

static const char *path_in(const test_env *env, const char *name, char *buf)
{
    snprintf(buf, PATH_CAP, "%s/%s", env->dir, name);
    return buf;
}

/* ---- particle files ---- */

/* A 40 x 40 x 6 jittered lattice of spacing 0.025 on z = 0 (like the shared
 * splash's pool), and with `droplet` one more particle at z = 2.1 above it. */
static fc_code pool(fc_frame *f, bool droplet, fc_error *err)
{
    const int n = 40, layers = 6;
    const double h = 0.025;
    fc_code code = fc_frame_alloc(f, (uint64_t)n * n * layers + (droplet ? 1 : 0), 0, err);
    if (code != FC_OK)
        return code;
    uint64_t i = 0;
    uint32_t seed = 777;
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
    if (droplet) {
        float *p = f->positions + 3 * i;
        p[0] = p[1] = 0.5f;
        p[2] = 2.1f;
    }
    return FC_OK;
}

static bool write_files(const test_env *env)
{
    char buf[PATH_CAP];
    fc_frame alone = { 0 }, with_droplet = { 0 }, ball = { 0 };
    bool ok = pool(&alone, false, NULL) == FC_OK && pool(&with_droplet, true, NULL) == FC_OK &&
              test_ball_frame(&ball, NULL) == FC_OK && mkdir(path_in(env, "seq", buf), 0777) == 0 &&
              test_write_f32(&alone, path_in(env, "pool.f32", buf)) &&
              test_write_f32(&with_droplet, path_in(env, "pool_droplet.f32", buf)) &&
              test_write_f32(&ball, path_in(env, "ball.f32", buf)) &&
              test_write_f32(&alone, path_in(env, "seq/f_0000.f32", buf)) &&
              test_write_f32(&with_droplet, path_in(env, "seq/f_0001.f32", buf)) &&
              test_write_f32(&alone, path_in(env, "seq/f_0002.f32", buf));
    fc_frame_free(&alone);
    fc_frame_free(&with_droplet);
    fc_frame_free(&ball);
    return ok;
}

/* ---- running the CLI ---- */

/* `fluidcast COMMAND INPUT -o OUTPUT` with the server, a 96x54 thickness AOV
 * and a fixed radius. */
static void run(const test_env *env, const char *command, const char *input, const char *output, cli_result *r)
{
    char in[PATH_CAP], out[PATH_CAP];
    const char *args[] = { command, path_in(env, input, in), "-o", path_in(env, output, out), "--server",
                           env->server, "--size", "96x54", "--aov", "thickness", "--radius", "0.02", NULL };
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
    CHECK_MSG(r->status == 0, "%s %s: exit %d: %s", command, input, r->status, r->err);
}

/* Where the thickness AOV is > 0: WIDTH x HEIGHT flags, or NULL. */
static bool *coverage(const test_env *env, const char *name)
{
    char path[PATH_CAP];
    bool *covered = aov_coverage(path_in(env, name, path), WIDTH, HEIGHT);
    CHECK_MSG(covered, "decoding %s", name);
    return covered;
}

static int differing(const bool *a, const bool *b)
{
    return coverage_difference(a, b, WIDTH * HEIGHT);
}

/* Columns from the leftmost to the rightmost fluid pixel. */
static int width_spanned(const bool *c)
{
    int left = WIDTH, right = -1;
    for (int y = 0; y < HEIGHT; y++)
        for (int x = 0; x < WIDTH; x++)
            if (c[y * WIDTH + x]) {
                left = x < left ? x : left;
                right = x > right ? x : right;
            }
    return right >= left ? right - left + 1 : 0;
}

/* Fluid pixels on the picture's edge: where fluid would run out of view. */
static int on_edge(const bool *c)
{
    int n = 0;
    for (int y = 0; y < HEIGHT; y++)
        for (int x = 0; x < WIDTH; x++)
            n += c[y * WIDTH + x] && (x == 0 || y == 0 || x == WIDTH - 1 || y == HEIGHT - 1);
    return n;
}

/* ---- tests ---- */

/* The droplet does not move the camera: the pool is framed as if alone (only
 * the droplet's own pixels may differ), large in the picture. */
static void test_droplet_left_out(const test_env *env)
{
    cli_result r;
    run(env, "snapshot", "pool.f32", "pool.exr", &r);
    CHECK_MSG(strstr(r.out, "framing:") == NULL, "stdout: %s", r.out);
    run(env, "snapshot", "pool_droplet.f32", "pool_droplet.exr", &r);
    CHECK_MSG(strstr(r.out, "\nframing: the fluid without 1 particle far from it (--eye/--target to frame them)\n"),
              "stdout: %s", r.out);
    bool *alone = coverage(env, "pool.exr"), *with_droplet = coverage(env, "pool_droplet.exr");
    if (alone && with_droplet) {
        CHECK_MSG(width_spanned(alone) >= WIDTH * 4 / 10, "the pool spans %d of %d columns", width_spanned(alone),
                  WIDTH);
        CHECK_MSG(width_spanned(with_droplet) >= WIDTH * 4 / 10, "with the droplet the pool spans %d of %d columns",
                  width_spanned(with_droplet), WIDTH);
        CHECK_MSG(differing(alone, with_droplet) <= 4, "%d pixels differ", differing(alone, with_droplet));
        CHECK_MSG(on_edge(alone) == 0, "%d fluid pixels on the edge", on_edge(alone));
    }
    free(alone);
    free(with_droplet);
}

/* pool, pool + droplet, pool: one camera, the pool's, for all three. */
static void test_sequence_keeps_the_pool_camera(const test_env *env)
{
    cli_result r;
    run(env, "render", "seq/f_%04d.f32", "seq/t_%04d.exr", &r);
    CHECK_MSG(strstr(r.out, "; camera framed on the bounds of 3 of them\n") &&
                  strstr(r.out, "\nframing: the fluid without up to 1 particle a frame far from it "
                                "(--eye/--target to frame them)\n"),
              "stdout: %s", r.out);
    bool *pictures[3], *alone = coverage(env, "pool.exr");
    for (int i = 0; i < 3; i++) {
        char name[32];
        snprintf(name, sizeof name, "seq/t_%04d.exr", i);
        pictures[i] = coverage(env, name);
    }
    if (pictures[0] && pictures[1] && pictures[2] && alone) {
        CHECK_MSG(width_spanned(pictures[0]) >= WIDTH * 4 / 10, "the pool spans %d of %d columns",
                  width_spanned(pictures[0]), WIDTH);
        CHECK_MSG(differing(pictures[0], pictures[2]) == 0, "%d pixels differ", differing(pictures[0], pictures[2]));
        CHECK_MSG(differing(pictures[0], pictures[1]) <= 4, "%d pixels differ", differing(pictures[0], pictures[1]));
        CHECK_MSG(differing(pictures[0], alone) <= 4, "render and snapshot: %d pixels differ",
                  differing(pictures[0], alone));
    }
    for (int i = 0; i < 3; i++)
        free(pictures[i]);
    free(alone);
}

/* A ball is compact: framed whole, nothing left out, nothing said. */
static void test_compact_framed_whole(const test_env *env)
{
    cli_result r;
    run(env, "snapshot", "ball.f32", "ball.exr", &r);
    CHECK_MSG(strstr(r.out, "framing:") == NULL, "stdout: %s", r.out);
    bool *ball = coverage(env, "ball.exr");
    if (ball) {
        int covered = 0;
        for (int i = 0; i < WIDTH * HEIGHT; i++)
            covered += ball[i];
        CHECK_MSG(covered > WIDTH * HEIGHT / 10, "%d fluid pixels", covered);
        CHECK_MSG(on_edge(ball) == 0, "%d fluid pixels on the edge", on_edge(ball));
    }
    free(ball);
}

static void remove_scratch(const test_env *env)
{
    const char *names[] = { "pool.f32", "pool_droplet.f32", "ball.f32", "pool.exr", "pool_droplet.exr", "ball.exr",
                            "seq/f_0000.f32", "seq/f_0001.f32", "seq/f_0002.f32", "seq/t_0000.exr",
                            "seq/t_0001.exr", "seq/t_0002.exr", "seq", "cli.stdout", "cli.stderr" };
    char path[PATH_CAP];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        remove(path_in(env, names[i], path));
    rmdir(env->dir);
}

int main(void)
{
    test_env env = { .dir = "/tmp/fluidcast-cli-framing-XXXXXX" };
    if (!mkdtemp(env.dir) || !write_files(&env)) {
        fprintf(stderr, "cannot set up the scratch directory\n");
        return 1;
    }
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        remove_scratch(&env);
        return 1;
    }
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_droplet_left_out(&env);
    test_sequence_keeps_the_pool_camera(&env);
    test_compact_framed_whole(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    remove_scratch(&env);
    return test_result();
}
