/* test_cli_render_bgeo.c — a SPlisHSPlasH-style particle sequence rendered
 * to an .mp4 in one command, against the real fluidcastd:
 *
 *     fluidcast render 'output/partio/ParticleData_Fluid_{}.bgeo' -o splash.mp4
 *
 * SPlisHSPlasH's partio exporter writes <output>/partio/ParticleData_<fluid
 * id>_<frame>.bgeo, the frame unpadded, gzip'd classic BGEO (V5) with the
 * point attributes "id" (int) and the exported fields ("velocity", a vector).
 * Eleven such files are built byte by byte here (the layout of
 * client/readers/reader_bgeo.c, gzip'd with zlib), frames 1..11 of a ball
 * moving along +x, so that name order (1, 10, 11, 2, ...) and number order
 * differ. The video is decoded with libavcodec: eleven frames, each within
 * 30 dB PSNR of the same sequence rendered to PNGs (f_0001.png ..
 * f_0011.png, numbered like the inputs), with the fluid's centroid moving
 * monotonically to the right. */
#define _GNU_SOURCE   /* mkdtemp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "render_pictures.h"
#include "support/daemon_process.h"
#include "support/tinted_look.h"
#include "test_util.h"
#include "video_frames.h"

#define FRAMES 11
#define WIDTH 160
#define HEIGHT 120
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

/* ---- classic BGEO as partio writes it (every number big-endian) ---- */

typedef struct bgeo_out {
    gzFile file;
    bool ok;
} bgeo_out;

static void put(bgeo_out *o, const void *bytes, unsigned n)
{
    o->ok = o->ok && gzwrite(o->file, bytes, n) == (int)n;
}

static void put_u32(bgeo_out *o, uint32_t v)
{
    const uint8_t b[4] = {(uint8_t)(v >> 24), (uint8_t)(v >> 16), (uint8_t)(v >> 8), (uint8_t)v};
    put(o, b, 4);
}

static void put_u16(bgeo_out *o, unsigned v)
{
    const uint8_t b[2] = {(uint8_t)(v >> 8), (uint8_t)v};
    put(o, b, 2);
}

static void put_f32(bgeo_out *o, float v)
{
    uint32_t bits;
    memcpy(&bits, &v, 4);
    put_u32(o, bits);
}

/* An attribute definition: name, components, type (0 float, 1 int, 5
 * vector), one zero default per component. */
static void put_attribute(bgeo_out *o, const char *name, unsigned components, uint32_t type)
{
    put_u16(o, (unsigned)strlen(name));
    put(o, name, (unsigned)strlen(name));
    put_u16(o, components);
    put_u32(o, type);
    for (unsigned k = 0; k < components; k++)
        put_u32(o, 0);
}

/* A ball of radius 0.15 (lattice spacing 0.05) centred at (cx, 0, 0.3),
 * moving along +x at 1: positions, "id" and "velocity". */
static bool write_frame(const char *path, float cx)
{
    const int n = 3;
    uint32_t count = 0;
    for (int a = -n; a <= n; a++)
        for (int b = -n; b <= n; b++)
            for (int c = -n; c <= n; c++)
                count += a * a + b * b + c * c <= n * n;
    bgeo_out o = {gzopen(path, "wb6"), true};
    if (!o.file)
        return false;
    put(&o, "BgeoV", 5);
    const uint32_t header[9] = {5, count, 0, 0, 0, 2, 0, 0, 0};   /* version, points, ..., 2 point attributes */
    for (int i = 0; i < 9; i++)
        put_u32(&o, header[i]);
    put_attribute(&o, "id", 1, 1);
    put_attribute(&o, "velocity", 3, 5);
    uint32_t id = 0;
    for (int a = -n; a <= n; a++)
        for (int b = -n; b <= n; b++)
            for (int c = -n; c <= n; c++) {
                if (a * a + b * b + c * c > n * n)
                    continue;
                const float p[4] = {cx + 0.05f * a, 0.05f * b, 0.3f + 0.05f * c, 1.0f};   /* x y z w */
                for (int k = 0; k < 4; k++)
                    put_f32(&o, p[k]);
                put_u32(&o, id++);
                const float v[3] = {1.0f, 0.0f, 0.0f};
                for (int k = 0; k < 3; k++)
                    put_f32(&o, v[k]);
            }
    put(&o, "\x00\xff", 2);   /* partio's beginExtra / endExtra */
    return gzclose(o.file) == Z_OK && o.ok;
}

static bool write_sequence(const test_env *env)
{
    char path[PATH_CAP];
    if (mkdir(path_in(env, "output", path), 0700) != 0 || mkdir(path_in(env, "output/partio", path), 0700) != 0)
        return false;
    for (int frame = 1; frame <= FRAMES; frame++) {
        char name[64];
        snprintf(name, sizeof name, "output/partio/ParticleData_Fluid_%d.bgeo", frame);
        if (!write_frame(path_in(env, name, path), -0.5f + 0.1f * (frame - 1)))
            return false;
    }
    return true;
}

/* ---- the render ---- */

static void render(const test_env *env, const char *out, const char *const *extra, cli_result *r)
{
    char in[PATH_CAP], o[PATH_CAP];
    const char *args[22] = {"render", path_in(env, "output/partio/ParticleData_Fluid_{}.bgeo", in), "-o",
                            path_in(env, out, o), "--server", env->server, "--size", "160x120", "--up", "z",
                            "--radius", "0.04", "--absorption", TINTED_LOOK_ABSORPTION};
    int n = 14;
    for (int i = 0; extra && extra[i] && n < 21; i++)
        args[n++] = extra[i];
    args[n] = NULL;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
}

static bool read_frame_png(const test_env *env, int frame, picture *out)
{
    char name[64], path[PATH_CAP];
    snprintf(name, sizeof name, "png/f_%04d.png", frame);
    return read_png(path_in(env, name, path), out);
}

static void test_pngs(const test_env *env, double centroid[FRAMES])
{
    cli_result r;
    render(env, "png/f_%04d.png", NULL, &r);
    CHECK_MSG(r.status == 0, "render to PNGs: exit %d\n%s%s", r.status, r.out, r.err);
    char first[PATH_CAP], last[PATH_CAP], expected[3 * PATH_CAP];
    snprintf(expected, sizeof expected, "render: %d frames, %s .. %s;", FRAMES,
             path_in(env, "output/partio/ParticleData_Fluid_1.bgeo", first),
             path_in(env, "output/partio/ParticleData_Fluid_11.bgeo", last));
    CHECK_MSG(strstr(r.out, expected), "expected \"%s\" in\n%s", expected, r.out);
    for (int i = 0; i < FRAMES; i++) {
        picture png;
        centroid[i] = -1;
        if (!read_frame_png(env, i + 1, &png)) {
            CHECK_MSG(0, "png/f_%04d.png missing or undecodable", i + 1);
            continue;
        }
        uint32_t pixels;
        centroid[i] = fluid_centroid_x(png.rgb, png.width, png.height, &pixels);
        CHECK_MSG(pixels > 30, "frame %d: %u fluid pixels", i + 1, pixels);
        if (i > 0)
            CHECK_MSG(centroid[i] > centroid[i - 1] + 1, "PNG centroids: frame %d at %.1f, frame %d at %.1f", i,
                      centroid[i - 1], i + 1, centroid[i]);
        free(png.rgb);
    }
}

static void test_video(const test_env *env, const double centroid[FRAMES])
{
    cli_result r;
    render(env, "splash.mp4", (const char *const[]){"--quality", "18", NULL}, &r);
    CHECK_MSG(r.status == 0, "render to mp4: exit %d\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(strstr(r.out, "rendered 11 frames to "), "stdout: %s", r.out);
    char path[PATH_CAP];
    video_frames v;
    if (!video_frames_read(path_in(env, "splash.mp4", path), &v)) {
        CHECK_MSG(0, "splash.mp4 does not decode");
        return;
    }
    CHECK_MSG(strcmp(v.codec, "h264") == 0, "codec %s", v.codec);
    CHECK_MSG(v.count == FRAMES, "splash.mp4: %u frames, expected %d", v.count, FRAMES);
    CHECK_MSG(v.width == WIDTH && v.height == HEIGHT, "splash.mp4: %ux%u", v.width, v.height);
    for (uint32_t i = 0; i < v.count && i < FRAMES && v.width == WIDTH && v.height == HEIGHT; i++) {
        picture png;
        if (!read_frame_png(env, (int)i + 1, &png))
            continue;
        double db = psnr(v.rgb[i], png.rgb, (size_t)WIDTH * HEIGHT * 3);
        uint32_t pixels;
        double cx = fluid_centroid_x(v.rgb[i], WIDTH, HEIGHT, &pixels);
        printf("splash.mp4 frame %u: PSNR %.1f dB against png/f_%04u.png; centroid x %.1f (PNG %.1f)\n", i, db,
               i + 1, cx, centroid[i]);
        CHECK_MSG(db > 30.0, "frame %u: PSNR %.1f dB", i, db);
        CHECK_MSG(fabs(cx - centroid[i]) < 2.0, "frame %u: centroid %.1f, PNG's %.1f", i, cx, centroid[i]);
        free(png.rgb);
    }
    video_frames_free(&v);
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
    test_env env = {.dir = "/tmp/fluidcast-render-bgeo-XXXXXX"};
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
    double centroid[FRAMES];
    test_pngs(&env, centroid);
    test_video(&env, centroid);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    if (getenv("FLUIDCAST_TEST_KEEP"))
        printf("kept %s\n", env.dir);
    else
        remove_tree(env.dir);
    return test_result();
}
