/* test_cli_camera_path.c — `fluidcast render --camera-path` against the real
 * fluidcastd. The analytic ball (test_ball.h) stands still in three frames,
 * ball_{}.f32; the keyframes put the eye on the -y axis 3 from the centre at
 * frame 0 and 5 at frame 2, so frame 1 is rendered from 4 (two keyframes:
 * a straight line at constant speed). The depth AOV of each frame's centre
 * pixel, which lies on the view axis, is the eye's distance minus the ball's
 * radius and the sphere radius, as the snapshot test checks for one camera.
 * Malformed files stop the render before it connects, with exit status 3 and
 * the file, line and column or keyframe and member named; --camera-path with
 * --orbit or --eye is a usage error. */
#define _GNU_SOURCE   /* mkdtemp */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "test_ball.h"
#include "test_util.h"

#define FRAMES 3
#define PATH_CAP 256

typedef struct test_env {
    char dir[64];
    char server[32];
} test_env;

static const char *path_in(const test_env *env, const char *name, char *buf)
{
    if (snprintf(buf, PATH_CAP, "%s/%s", env->dir, name) >= PATH_CAP)
        buf[0] = '\0';
    return buf;
}

static bool write_text(const test_env *env, const char *name, const char *text)
{
    char path[PATH_CAP];
    FILE *f = fopen(path_in(env, name, path), "w");
    bool ok = f && fputs(text, f) >= 0;
    return f && fclose(f) == 0 && ok;
}

static bool write_sequence(const test_env *env)
{
    fc_frame ball;
    fc_error err;
    if (test_ball_frame(&ball, &err) != FC_OK)
        return false;
    bool ok = true;
    for (int i = 0; i < FRAMES && ok; i++) {
        char name[32], path[PATH_CAP];
        snprintf(name, sizeof name, "ball_%d.f32", i);
        ok = test_write_f32(&ball, path_in(env, name, path));
    }
    fc_frame_free(&ball);
    return ok;
}

/* render ball_{}.f32 -o OUT --camera-path CAMERA, then `extra`. */
static void render(const test_env *env, const char *camera, const char *out, const char *const *extra,
                   cli_result *r)
{
    char in[PATH_CAP], cam[PATH_CAP], o[PATH_CAP];
    const char *args[24] = {"render", path_in(env, "ball_{}.f32", in), "-o", path_in(env, out, o), "--camera-path",
                            path_in(env, camera, cam), "--server", env->server, "--radius", "0.05"};
    int n = 10;
    for (int i = 0; extra && extra[i] && n < 23; i++)
        args[n++] = extra[i];
    args[n] = NULL;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
}

static double centre_depth(const test_env *env, int frame)
{
    char name[32], path[PATH_CAP];
    snprintf(name, sizeof name, "depth/d_%04d.exr", frame);
    size_t size;
    uint8_t *data = read_whole_file(path_in(env, name, path), &size);
    fc_decoded_image img;
    fc_error err;
    fc_code code = data ? fc_decode_image(data, size, "exr", 1, &img, &err) : FC_ERR_IO;
    free(data);
    CHECK_MSG(code == FC_OK, "decoding %s: %s", path, data ? err.message : "unreadable");
    if (code != FC_OK)
        return -1.0;
    double depth = -1.0;
    if (img.width == 161 && img.height == 121 && img.channels == 1)
        depth = ((const float *)img.pixels)[60 * 161 + 80];
    fc_decoded_image_free(&img);
    return depth;
}

static void test_interpolated_depth(const test_env *env)
{
    CHECK(write_text(env, "cam.json",
                     "{ \"keyframes\": [\n"
                     "  { \"frame\": 0, \"eye\": [0, -3, 0], \"target\": [0, 0, 0], \"up\": [0, 0, 1], \"fov\": 40 },\n"
                     "  { \"frame\": 2, \"eye\": [0, -5, 0], \"target\": [0, 0, 0], \"up\": [0, 0, 1], \"fov\": 40 }\n"
                     "] }\n"));
    cli_result r;
    render(env, "cam.json", "depth/d_%04d.exr", (const char *const[]){"--aov", "depth", "--size", "161x121", NULL},
           &r);
    CHECK_MSG(r.status == 0, "exit %d\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(strstr(r.out, "camera from ") && strstr(r.out, "cam.json (2 keyframes)"), "%s", r.out);
    for (int i = 0; i < FRAMES; i++) {
        double eye_distance = 3.0 + i, expected = eye_distance - BALL_RADIUS - BALL_SPHERE_RADIUS;
        double depth = centre_depth(env, i);
        printf("frame %d: eye %.1f from the centre, depth at the centre %.4f (expected %.4f)\n", i, eye_distance,
               depth, expected);
        CHECK_NEAR(depth, expected, 0.02 * expected);
    }
}

static void expect_failure(const test_env *env, const char *camera, const char *const *extra, int status,
                           const char *message)
{
    cli_result r;
    render(env, camera, "never/f_%04d.png", extra, &r);
    CHECK_MSG(r.status == status && strstr(r.err, message), "%s: exit %d (expected %d), expected \"%s\" in\n%s",
              camera, r.status, status, message, r.err);
    CHECK_MSG(!strstr(r.out, "render: "), "%s: the render started:\n%s", camera, r.out);
}

static void test_malformed_files(const test_env *env)
{
    char line[PATH_CAP + 96], path[PATH_CAP];
    CHECK(write_text(env, "syntax.json", "[\n  { \"frame\": 0, \"eye\": [0, -3, 0] \"target\": [0, 0, 0] }\n]\n"));
    snprintf(line, sizeof line, "%s:2:", path_in(env, "syntax.json", path));
    expect_failure(env, "syntax.json", NULL, 3, line);
    CHECK(write_text(env, "missing.json", "[ { \"frame\": 0, \"eye\": [0, -3, 0] } ]"));
    expect_failure(env, "missing.json", NULL, 3, "keyframe 1: \"target\" is missing");
    CHECK(write_text(env, "order.json", "[ { \"frame\": 2, \"eye\": [0, -3, 0], \"target\": [0, 0, 0] },\n"
                                        "  { \"frame\": 1, \"eye\": [0, -5, 0], \"target\": [0, 0, 0] } ]"));
    expect_failure(env, "order.json", NULL, 3, "keyframe 2 is at frame 1, not after keyframe 1's frame 2");
    /* Below 180 as a double, 180.0f as the float sent: refused here, not by the daemon (exit 5). */
    CHECK(write_text(env, "fov180.json", "[ { \"frame\": 0, \"eye\": [0, -3, 0], \"target\": [0, 0, 0], "
                                         "\"fov\": 179.99999999995 } ]"));
    snprintf(line, sizeof line, "%s: keyframe 1: \"fov\" must be a number of degrees in (0, 180)",
             path_in(env, "fov180.json", path));
    expect_failure(env, "fov180.json", NULL, 3, line);
    expect_failure(env, "absent.json", NULL, 3, "absent.json: cannot open: No such file or directory");
    expect_failure(env, "cam.json", (const char *const[]){"--orbit", "90", NULL}, 2, "leave out --orbit");
    expect_failure(env, "cam.json", (const char *const[]){"--eye", "0,-3,0", "--target", "0,0,0", NULL}, 2,
                   "leave out --eye and --target");
}

static void remove_tree(const char *dir)
{
    char command[PATH_CAP + 16];
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    if (system(command) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
}

int main(void)
{
    test_env env = {.dir = "/tmp/fluidcast-camera-path-XXXXXX"};
    if (!mkdtemp(env.dir) || !write_sequence(&env)) {
        fprintf(stderr, "cannot set up the scratch directory\n");
        return 1;
    }
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        remove_tree(env.dir);
        return 1;
    }
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_interpolated_depth(&env);
    test_malformed_files(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    if (getenv("FLUIDCAST_TEST_KEEP"))
        printf("kept %s\n", env.dir);
    else
        remove_tree(env.dir);
    return test_result();
}
