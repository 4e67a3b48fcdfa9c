/* test_cli_render.c — `fluidcast render` against the real fluidcastd: six
 * frames of a ball of particles moving along +x, rendered at 160x120 to PNGs
 * and to an .mp4 (and a .webm). The videos are decoded with libavformat and
 * libavcodec: as many frames as files, in order (the ball's centroid moves
 * monotonically, as in the PNGs), each within a PSNR bound of its PNG.
 * --skip-existing renders only the missing images and leaves the others
 * untouched; a missing or corrupt frame in the middle stops the render with
 * exit status 3 and its name, and the partial video plays with the frames
 * before it, as it does after Ctrl-C; --orbit 90 turns the view (the floor changes between the first
 * and last frame) while the fixed camera keeps every pixel away from the
 * ball. Inputs as a glob, a %d pattern and a {} pattern come in number order
 * (b_2 before b_10), with --start/--end/--step; a {} pattern refuses two
 * files of one number and a range without frames. */
#define _GNU_SOURCE   /* memmem */
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli_runner.h"
#include "render_pictures.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "support/daemon_process.h"
#include "support/tinted_look.h"
#include "test_ball.h"
#include "test_util.h"
#include "video_frames.h"

#define FRAMES 6
#define WIDTH 160
#define HEIGHT 120
#define PATH_CAP 256

typedef struct test_env {
    char dir[64];
    char server[32];
} test_env;

static const char *path_in(const test_env *env, const char *name, char *buf)
{
    if (snprintf(buf, PATH_CAP, "%s/%s", env->dir, (const char *)name) >= PATH_CAP)
        buf[0] = '\0';
    return buf;
}

static const char *frame_input(const test_env *env, int i, char *buf)
{
    snprintf(buf, PATH_CAP, "%s/in/ball_%04d.f32", env->dir, i);
    return buf;
}

/* ---- the sequence: a ball of radius 0.15 (lattice spacing 0.05) whose
 * centre moves from x = -0.5 to x = 0.5, 0.3 above the origin ---- */

static bool write_ball(const char *path, float cx)
{
    const int n = 3;
    fc_frame f = {0};
    if (fc_frame_alloc(&f, (uint64_t)(2 * n + 1) * (2 * n + 1) * (2 * n + 1), 0, NULL) != FC_OK)
        return false;
    uint64_t count = 0;
    for (int a = -n; a <= n; a++)
        for (int b = -n; b <= n; b++)
            for (int c = -n; c <= n; c++) {
                if (a * a + b * b + c * c > n * n)
                    continue;
                float *p = f.positions + 3 * count++;
                p[0] = cx + 0.05f * a;
                p[1] = 0.05f * b;
                p[2] = 0.3f + 0.05f * c;
            }
    f.count = count;
    bool ok = test_write_f32(&f, path);
    fc_frame_free(&f);
    return ok;
}

static bool write_sequence(const test_env *env)
{
    char buf[PATH_CAP];
    if (mkdir(path_in(env, "in", buf), 0700) != 0)
        return false;
    for (int i = 0; i < FRAMES; i++)
        if (!write_ball(frame_input(env, i, buf), -0.5f + 0.2f * i))
            return false;
    /* Corrupt: 5 bytes are not whole xyz float triples. */
    FILE *f = fopen(path_in(env, "in/corrupt.f32", buf), "wb");
    return f && fwrite("abcde", 1, 5, f) == 5 && fclose(f) == 0;
}

/* ---- running the CLI ---- */

/* The CLI with the common options first, then `extra` (NULL-terminated). */
static void render(const test_env *env, const char *const *inputs, const char *out, const char *const *extra,
                   cli_result *r)
{
    const char *args[31] = {"render"};
    int n = 1;
    for (int i = 0; inputs[i] && n < 20; i++)
        args[n++] = inputs[i];
    const char *common[] = {"-o", out, "--server", env->server, "--size", "160x120", "--up", "z", "--radius",
                            "0.04", "--absorption", TINTED_LOOK_ABSORPTION, NULL};
    for (int i = 0; common[i]; i++)
        args[n++] = common[i];
    for (int i = 0; extra && extra[i] && n < 30; i++)
        args[n++] = extra[i];
    args[n] = NULL;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
}

static const char *pattern_input(const test_env *env, char *buf)
{
    snprintf(buf, PATH_CAP, "%s/in/ball_%%04d.f32", env->dir);
    return buf;
}

/* ---- pictures ---- */

static bool read_frame_png(const char *pattern_dir, const test_env *env, int i, picture *out)
{
    char name[PATH_CAP], path[PATH_CAP];
    snprintf(name, sizeof name, "%s/f_%04d.png", pattern_dir, i);
    return read_png(path_in(env, name, path), out);
}

/* Fraction of the pixels of rows [first_row, height) where some channel
 * differs by more than 2. */
static double changed_fraction(const picture *a, const picture *b, uint32_t first_row)
{
    size_t n = (size_t)a->width * a->height, changed = 0;
    for (size_t p = (size_t)first_row * a->width; p < n; p++)
        for (int c = 0; c < 3; c++)
            if (abs((int)a->rgb[3 * p + c] - (int)b->rgb[3 * p + c]) > 2) {
                changed++;
                break;
            }
    return (double)changed / (double)(n - (size_t)first_row * a->width);
}

/* ---- the tests ---- */

static void test_png_sequence(const test_env *env, double centroid[FRAMES])
{
    char in[PATH_CAP], out[PATH_CAP];
    cli_result r;
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "png/f_%04d.png", out), NULL, &r);
    CHECK_MSG(r.status == 0, "render to PNGs: exit %d\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(strstr(r.out, "render: 6 frames") && strstr(r.out, "frame 6/6 ") &&
                  strstr(r.out, "rendered 6 frames to "),
              "stdout: %s", r.out);
    for (int i = 0; i < FRAMES; i++) {
        picture png;
        centroid[i] = -1;
        if (!read_frame_png("png", env, i, &png)) {
            CHECK_MSG(0, "png/f_%04d.png missing or undecodable", i);
            continue;
        }
        CHECK(png.width == WIDTH && png.height == HEIGHT);
        uint32_t pixels;
        centroid[i] = fluid_centroid_x(png.rgb, png.width, png.height, &pixels);
        CHECK_MSG(pixels > 30, "frame %d: %u fluid pixels", i, pixels);
        if (i > 0)
            CHECK_MSG(centroid[i] > centroid[i - 1] + 3, "PNG centroids: frame %d at %.1f, frame %d at %.1f", i - 1,
                      centroid[i - 1], i, centroid[i]);
        free(png.rgb);
    }
}

/* --mesh with a %04d pattern: frame i reads box_000i.obj. Odd frames put an
 * opaque grey box around that frame's ball, even ones put it far to the side:
 * the ball shows in even frames only (no blue pixel in odd ones). */
static void test_per_frame_mesh(const test_env *env)
{
    char buf[PATH_CAP];
    bool ok = true;
    for (int i = 0; i < FRAMES && ok; i++) {
        char name[64];
        snprintf(name, sizeof name, "in/box_%04d.obj", i);
        FILE *f = fopen(path_in(env, name, buf), "w");
        if (!f) {
            ok = false;
            break;
        }
        float cx = i % 2 ? -0.5f + 0.2f * i : 10.0f, lo[3] = {cx - 0.25f, -0.25f, 0.05f},
              hi[3] = {cx + 0.25f, 0.25f, 0.55f};
        for (int c = 0; c < 8; c++)
            fprintf(f, "v %g %g %g\n", (double)(c & 1 ? hi[0] : lo[0]), (double)(c & 2 ? hi[1] : lo[1]),
                    (double)(c & 4 ? hi[2] : lo[2]));
        fputs("f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n", f);
        ok = fclose(f) == 0;
    }
    CHECK(ok);
    char in[PATH_CAP], out[PATH_CAP], mesh[PATH_CAP];
    cli_result r;
    snprintf(mesh, sizeof mesh, "%s/in/box_%%04d.obj", env->dir);
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "mesh/f_%04d.png", out),
           (const char *const[]){"--mesh", mesh, NULL}, &r);
    CHECK_MSG(r.status == 0, "render with a per-frame mesh: exit %d\n%s%s", r.status, r.out, r.err);
    for (int i = 0; i < FRAMES && r.status == 0; i++) {
        picture png;
        if (!read_frame_png("mesh", env, i, &png)) {
            CHECK_MSG(0, "mesh/f_%04d.png missing or undecodable", i);
            continue;
        }
        uint32_t pixels;
        fluid_centroid_x(png.rgb, png.width, png.height, &pixels);
        CHECK_MSG(i % 2 ? pixels == 0 : pixels > 30, "frame %d with its box: %u fluid pixels", i, pixels);
        free(png.rgb);
    }
    /* A frame whose mesh file is missing stops the render with an input error naming it. */
    snprintf(mesh, sizeof mesh, "%s/in/nobox_%%04d.obj", env->dir);
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "nomesh/f_%04d.png", out),
           (const char *const[]){"--mesh", mesh, NULL}, &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "nobox_0000.obj"), "missing per-frame mesh: exit %d: %s", r.status, r.err);
}

/* --mesh FILE:transforms=PLACEMENTS: one static box about the origin, moved
 * per frame by a 3x4 matrix: onto the ball in odd frames (x = its centre),
 * far aside in even ones; the ball shows in even frames only. A placements
 * line that is not a frame and 12 numbers (finite as floats) is an input error
 * naming the line. */
static void test_mesh_transforms(const test_env *env)
{
    char box[PATH_CAP], placements[PATH_CAP], bad[PATH_CAP];
    FILE *f = fopen(path_in(env, "in/rigid.obj", box), "w");
    FILE *p = fopen(path_in(env, "in/rigid.txt", placements), "w");
    FILE *b = fopen(path_in(env, "in/rigid_bad.txt", bad), "w");
    CHECK(f && p && b);
    if (!f || !p || !b) {
        if (f)
            fclose(f);
        if (p)
            fclose(p);
        if (b)
            fclose(b);
        return;
    }
    const float lo[3] = {-0.25f, -0.25f, 0.05f}, hi[3] = {0.25f, 0.25f, 0.55f};
    for (int c = 0; c < 8; c++)
        fprintf(f, "v %g %g %g\n", (double)(c & 1 ? hi[0] : lo[0]), (double)(c & 2 ? hi[1] : lo[1]),
                (double)(c & 4 ? hi[2] : lo[2]));
    fputs("f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n", f);
    fputs("# frame, then the 3x4 matrix row by row\n", p);
    for (int i = 0; i < FRAMES; i++)
        fprintf(p, "%d 1 0 0 %g 0 1 0 0 0 0 1 0\n", i, i % 2 ? -0.5 + 0.2 * i : 10.0);
    fputs("0 1 0 0 0 0 1 0\n", b);
    CHECK(fclose(f) == 0 && fclose(p) == 0 && fclose(b) == 0);
    char in[PATH_CAP], out[PATH_CAP], mesh[2 * PATH_CAP + 16];
    cli_result r;
    snprintf(mesh, sizeof mesh, "%s:transforms=%s", box, placements);
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "rigid/f_%04d.png", out),
           (const char *const[]){"--mesh", mesh, NULL}, &r);
    CHECK_MSG(r.status == 0, "render with placements: exit %d\n%s%s", r.status, r.out, r.err);
    for (int i = 0; i < FRAMES && r.status == 0; i++) {
        picture png;
        if (!read_frame_png("rigid", env, i, &png)) {
            CHECK_MSG(0, "rigid/f_%04d.png missing or undecodable", i);
            continue;
        }
        uint32_t pixels;
        fluid_centroid_x(png.rgb, png.width, png.height, &pixels);
        CHECK_MSG(i % 2 ? pixels == 0 : pixels > 30, "frame %d with the box placed: %u fluid pixels", i, pixels);
        free(png.rgb);
    }
    snprintf(mesh, sizeof mesh, "%s:transforms=%s", box, bad);
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "rigid_bad/f_%04d.png", out),
           (const char *const[]){"--mesh", mesh, NULL}, &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "rigid_bad.txt: line 1"), "bad placements: exit %d: %s", r.status, r.err);
    /* A frame beyond uint32_t and a matrix entry finite as a double but not as the float sent. */
    const char *const out_of_range[] = {"5000000000 1 0 0 0 0 1 0 0 0 0 1 0\n", "0 1 0 0 1e39 0 1 0 0 0 0 1 0\n"};
    for (int k = 0; k < 2; k++) {
        FILE *o = fopen(path_in(env, "in/rigid_range.txt", bad), "w");
        CHECK(o && fputs(out_of_range[k], o) >= 0 && fclose(o) == 0);
        snprintf(mesh, sizeof mesh, "%s:transforms=%s", box, bad);
        render(env, (const char *const[]){pattern_input(env, in), NULL},
               path_in(env, "rigid_range/f_%04d.png", out), (const char *const[]){"--mesh", mesh, NULL}, &r);
        CHECK_MSG(r.status == 3 && strstr(r.err, "rigid_range.txt: line 1"), "%s: exit %d: %s", out_of_range[k],
                  r.status, r.err);
    }
}

/* The video has the PNGs' frames, in their order, within `min_psnr` dB. */
static void check_video(const test_env *env, const char *name, const char *codec, const double centroid[FRAMES],
                        double min_psnr)
{
    char path[PATH_CAP];
    video_frames v;
    if (!video_frames_read(path_in(env, name, path), &v)) {
        CHECK_MSG(0, "%s does not decode", name);
        return;
    }
    CHECK_MSG(strcmp(v.codec, codec) == 0, "%s: codec %s, expected %s", name, v.codec, codec);
    CHECK_MSG(v.count == FRAMES, "%s: %u frames, expected %d", name, v.count, FRAMES);
    CHECK_MSG(v.width == WIDTH && v.height == HEIGHT, "%s: %ux%u", name, v.width, v.height);
    for (uint32_t i = 0; i < v.count && i < FRAMES && v.width == WIDTH && v.height == HEIGHT; i++) {
        picture png;
        if (!read_frame_png("png", env, (int)i, &png))
            continue;
        double db = psnr(v.rgb[i], png.rgb, (size_t)WIDTH * HEIGHT * 3);
        uint32_t pixels;
        double cx = fluid_centroid_x(v.rgb[i], WIDTH, HEIGHT, &pixels);
        printf("%s frame %u: PSNR %.1f dB against the PNG; centroid x %.1f (PNG %.1f)\n", name, i, db, cx,
               centroid[i]);
        CHECK_MSG(db > min_psnr, "%s frame %u: PSNR %.1f dB against png/f_%04u.png", name, i, db, i);
        CHECK_MSG(fabs(cx - centroid[i]) < 2.0, "%s frame %u: centroid %.1f, PNG's %.1f", name, i, cx, centroid[i]);
        free(png.rgb);
    }
    video_frames_free(&v);
}

static void test_videos(const test_env *env, const double centroid[FRAMES])
{
    char in[PATH_CAP], out[PATH_CAP];
    cli_result r;
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "seq.mp4", out),
           (const char *const[]){"--quality", "18", NULL}, &r);
    CHECK_MSG(r.status == 0, "render to mp4: exit %d\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(strstr(r.out, "libx264, yuv420p, 160x120, crf 18, 24 fps"), "stdout: %s", r.out);
    check_video(env, "seq.mp4", "h264", centroid, 30.0);

    /* A glob, sorted by the numbers in the names, into VP9. */
    snprintf(in, sizeof in, "%s/in/ball_*.f32", env->dir);
    render(env, (const char *const[]){in, NULL}, path_in(env, "seq.webm", out), NULL, &r);
    CHECK_MSG(r.status == 0, "render to webm: exit %d\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(strstr(r.out, "libvpx-vp9"), "stdout: %s", r.out);
    check_video(env, "seq.webm", "vp9", centroid, 30.0);
}

static bool same_mtime(const struct stat *a, const struct stat *b)
{
    return a->st_mtim.tv_sec == b->st_mtim.tv_sec && a->st_mtim.tv_nsec == b->st_mtim.tv_nsec;
}

static void test_skip_existing(const test_env *env)
{
    char in[PATH_CAP], out[PATH_CAP], path[PATH_CAP], name[PATH_CAP];
    struct stat before[FRAMES];
    for (int i = 0; i < FRAMES; i++) {
        snprintf(name, sizeof name, "png/f_%04d.png", i);
        CHECK(stat(path_in(env, name, path), &before[i]) == 0);
    }
    CHECK(unlink(path_in(env, "png/f_0002.png", path)) == 0);
    CHECK(unlink(path_in(env, "png/f_0004.png", path)) == 0);
    cli_result r;
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "png/f_%04d.png", out),
           (const char *const[]){"--skip-existing", NULL}, &r);
    CHECK_MSG(r.status == 0, "--skip-existing: exit %d\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(strstr(r.out, "skipping 4 frames whose images exist") && strstr(r.out, "frame 2/2 ") &&
                  strstr(r.out, "ball_0004.f32") && !strstr(r.out, "ball_0003.f32:"),
              "stdout: %s", r.out);
    for (int i = 0; i < FRAMES; i++) {
        struct stat now;
        snprintf(name, sizeof name, "png/f_%04d.png", i);
        CHECK_MSG(stat(path_in(env, name, path), &now) == 0, "%s missing", name);
        if (i != 2 && i != 4)
            CHECK_MSG(same_mtime(&before[i], &now), "%s was rewritten", name);
    }
}

static void test_missing_and_corrupt_frames(const test_env *env)
{
    char in[FRAMES][PATH_CAP], out[PATH_CAP], path[PATH_CAP];
    for (int i = 0; i < FRAMES; i++)
        frame_input(env, i, in[i]);
    snprintf(in[3], PATH_CAP, "%s/in/ball_missing.f32", env->dir);
    cli_result r;
    render(env, (const char *const[]){in[0], in[1], in[2], in[3], in[4], in[5], NULL}, path_in(env, "part.mp4", out),
           NULL, &r);
    CHECK_MSG(r.status == 3, "missing frame: exit %d\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(strstr(r.err, "frame 4 of 6") && strstr(r.err, in[3]), "stderr: %s", r.err);
    CHECK_MSG(strstr(r.err, "part.mp4 is finished with the 3 frames rendered before it stopped"), "stderr: %s",
              r.err);
    video_frames v;
    CHECK_MSG(video_frames_read(path_in(env, "part.mp4", path), &v) && v.count == 3,
              "the partial video decodes to %u frames, expected 3", v.count);
    video_frames_free(&v);

    snprintf(in[3], PATH_CAP, "%s/in/corrupt.f32", env->dir);
    render(env, (const char *const[]){in[0], in[1], in[2], in[3], in[4], NULL}, path_in(env, "corrupt/f_%d.png", out),
           NULL, &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "frame 4 of 5") && strstr(r.err, "corrupt.f32"),
              "corrupt frame: exit %d: %s", r.status, r.err);
    CHECK_MSG(access(path_in(env, "corrupt/f_2.png", path), F_OK) == 0 &&
                  access(path_in(env, "corrupt/f_3.png", path), F_OK) != 0,
              "the images before the corrupt frame are written, none after");

    /* A pattern with --end wants every frame up to it. */
    char pattern[PATH_CAP];
    render(env, (const char *const[]){pattern_input(env, pattern), NULL}, path_in(env, "end.mp4", out),
           (const char *const[]){"--start", "4", "--end", "7", NULL}, &r);
    CHECK_MSG(r.status == 3 && strstr(r.err, "frame 3 of 4") && strstr(r.err, "ball_0006.f32"),
              "--end past the last file: exit %d: %s", r.status, r.err);
}

extern char **environ;

/* Waits up to 30 s for `text` in the file at `path`. */
static bool wait_for_text(const char *path, const char *text)
{
    for (int i = 0; i < 3000; i++) {
        size_t size;
        uint8_t *data = read_whole_file(path, &size);
        bool found = data && memmem(data, size, text, strlen(text)) != NULL;
        free(data);
        if (found)
            return true;
        nanosleep(&(struct timespec){.tv_nsec = 10 * 1000 * 1000}, NULL);
    }
    return false;
}

/* SIGINT once the second frame is out: the render stops after the frame in
 * flight with status 130, and the video plays. 48 frames (the six, eight
 * times) take seconds, so the signal comes long before the end. */
static void test_interrupt(const test_env *env)
{
    enum { REPEATS = 8 };
    char in[FRAMES][PATH_CAP], out[PATH_CAP], log[PATH_CAP], err_log[PATH_CAP];
    const char *argv[FRAMES * REPEATS + 16] = {FLUIDCAST_CLI_PATH, "render"};
    int n = 2;
    for (int i = 0; i < FRAMES; i++)
        frame_input(env, i, in[i]);
    for (int r = 0; r < REPEATS; r++)
        for (int i = 0; i < FRAMES; i++)
            argv[n++] = in[i];
    const char *common[] = {"-o", path_in(env, "stopped.mp4", out), "--server", env->server, "--size", "160x120",
                            "--up", "z", "--radius", "0.04", NULL};
    for (int i = 0; common[i]; i++)
        argv[n++] = common[i];
    argv[n] = NULL;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, path_in(env, "stopped.out", log),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, path_in(env, "stopped.err", err_log),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0600);
    pid_t pid;
    int status = 0;
    CHECK(posix_spawn(&pid, FLUIDCAST_CLI_PATH, &actions, NULL, (char *const *)argv, environ) == 0);
    posix_spawn_file_actions_destroy(&actions);
    CHECK_MSG(wait_for_text(log, "frame 2/48 "), "the render did not get to its second frame");
    kill(pid, SIGINT);
    CHECK(waitpid(pid, &status, 0) == pid);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 130, "interrupted render: status 0x%x", status);
    size_t size;
    uint8_t *bytes = read_whole_file(err_log, &size);
    char err[CLI_CAPTURE_MAX] = "";
    if (bytes)
        memcpy(err, bytes, size < sizeof err - 1 ? size : sizeof err - 1);
    free(bytes);
    CHECK_MSG(strstr(err, "interrupted after") && strstr(err, "stopped.mp4 is finished with the"), "stderr: %s",
              err);
    video_frames v;
    CHECK_MSG(video_frames_read(out, &v) && v.count >= 2 && v.count < FRAMES * REPEATS,
              "the interrupted video decodes to %u frames", v.count);
    printf("SIGINT after frame 2 of 48: exit 130, the video decodes to %u frames\n", v.count);
    video_frames_free(&v);
}

static void test_orbit(const test_env *env)
{
    char in[PATH_CAP], out[PATH_CAP];
    cli_result r;
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, "orbit/f_%04d.png", out),
           (const char *const[]){"--orbit", "90", NULL}, &r);
    CHECK_MSG(r.status == 0, "--orbit: exit %d\n%s%s", r.status, r.out, r.err);
    picture fixed_first, fixed_last, orbit_first, orbit_last;
    if (!read_frame_png("png", env, 0, &fixed_first) || !read_frame_png("png", env, FRAMES - 1, &fixed_last) ||
        !read_frame_png("orbit", env, 0, &orbit_first) || !read_frame_png("orbit", env, FRAMES - 1, &orbit_last)) {
        CHECK_MSG(0, "cannot read the fixed and orbit images");
        return;
    }
    /* The bottom rows show the near floor's checkers, which neither the ball
     * nor its shadow reaches: the background. */
    uint32_t floor_rows = HEIGHT - 16;
    double fixed = changed_fraction(&fixed_first, &fixed_last, floor_rows);
    double orbit = changed_fraction(&orbit_first, &orbit_last, floor_rows);
    double start = changed_fraction(&fixed_first, &orbit_first, 0);
    printf("background (bottom 16 rows) changed first to last: fixed camera %.1f%%, --orbit 90 %.1f%%; orbit's "
           "first frame against the fixed one: %.1f%% of all pixels\n",
           100 * fixed, 100 * orbit, 100 * start);
    CHECK_MSG(fixed == 0.0, "fixed camera: %.1f%% of the background changes", 100 * fixed);
    CHECK_MSG(orbit > 0.4, "--orbit 90: only %.1f%% of the background changes", 100 * orbit);
    CHECK_MSG(start == 0.0, "--orbit starts from the fixed camera: %.2f%% differ", 100 * start);
    free(fixed_first.rgb);
    free(fixed_last.rgb);
    free(orbit_first.rgb);
    free(orbit_last.rgb);
}

/* Which files the inputs name, in which order: the first line says, before
 * the connection to a server that is not there fails (exit 4). Files b_1,
 * b_2 and b_10, unpadded. */
static void expect_frames(const test_env *env, const char *input, const char *const *extra, const char *expected)
{
    char in[PATH_CAP], out[PATH_CAP], line[2 * PATH_CAP];
    const char *args[16] = {"render", path_in(env, input, in), "-o", path_in(env, "never.mp4", out), "--server",
                            "127.0.0.1:1", "--up", "z"};
    int n = 8;
    for (int i = 0; extra && extra[i] && n < 15; i++)
        args[n++] = extra[i];
    args[n] = NULL;
    cli_result r;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, &r);
    snprintf(line, sizeof line, "render: %s", expected);
    CHECK_MSG(r.status == 4 && strstr(r.out, line), "%s: exit %d, expected \"%s\" in\n%s%s", input, r.status,
              expected, r.out, r.err);
}

static void test_input_order(const test_env *env)
{
    char from[PATH_CAP], to[PATH_CAP], a[PATH_CAP], b[PATH_CAP];
    const int numbers[] = {1, 2, 10};
    CHECK(mkdir(path_in(env, "un", to), 0700) == 0);
    for (int i = 0; i < 3; i++) {
        snprintf(a, sizeof a, "un/b_%d.f32", numbers[i]);
        CHECK(link(frame_input(env, i, from), path_in(env, a, to)) == 0);
    }
    path_in(env, "un/b_1.f32", a);
    path_in(env, "un/b_10.f32", b);
    char expected[3 * PATH_CAP];
    snprintf(expected, sizeof expected, "3 frames, %s .. %s; camera framed on the bounds of 3 of them", a, b);
    expect_frames(env, "un/b_*.f32", NULL, expected);   /* 10 after 2 */
    path_in(env, "un/b_2.f32", b);
    snprintf(expected, sizeof expected, "2 frames, %s .. %s;", a, b);
    expect_frames(env, "un/b_%d.f32", NULL, expected);   /* from the lowest, up to the first missing */
    path_in(env, "un/b_2.f32", a);
    path_in(env, "un/b_10.f32", b);
    snprintf(expected, sizeof expected, "2 frames, %s .. %s;", a, b);
    expect_frames(env, "un/b_%d.f32", (const char *const[]){"--start", "2", "--step", "8", NULL}, expected);
    /* {}: every file with digits there, by number, gaps allowed. */
    path_in(env, "un/b_1.f32", a);
    snprintf(expected, sizeof expected, "3 frames, %s .. %s; camera framed on the bounds of 3 of them", a, b);
    expect_frames(env, "un/b_{}.f32", NULL, expected);
    snprintf(expected, sizeof expected, "2 frames, %s .. %s;", a, b);
    expect_frames(env, "un/b_{}.f32", (const char *const[]){"--step", "9", NULL}, expected);   /* 1 and 10 */
    path_in(env, "un/b_2.f32", a);
    snprintf(expected, sizeof expected, "1 frames, %s .. %s;", a, a);
    expect_frames(env, "un/b_{}.f32", (const char *const[]){"--start", "2", "--end", "9", NULL}, expected);
}

/* A {} pattern refuses two files of one number, a pattern that matches
 * nothing and a range with none of its frames, naming the files. */
static void test_brace_pattern_errors(const test_env *env)
{
    char a[PATH_CAP], b[PATH_CAP], in[PATH_CAP], out[PATH_CAP], message[3 * PATH_CAP];
    CHECK(mkdir(path_in(env, "dup", a), 0700) == 0);
    CHECK(link(frame_input(env, 0, a), path_in(env, "dup/c_1.f32", b)) == 0);
    CHECK(link(frame_input(env, 1, a), path_in(env, "dup/c_01.f32", b)) == 0);
    CHECK(link(frame_input(env, 2, a), path_in(env, "dup/c_x.f32", b)) == 0);   /* no digits: not a frame */
    snprintf(message, sizeof message, "%s and %s are both frame 1", path_in(env, "dup/c_01.f32", a),
             path_in(env, "dup/c_1.f32", b));
    const struct {
        const char *input, *extra, *message;
    } cases[] = {
        {"dup/c_{}.f32", NULL, message},
        {"dup/d_{}.f32", NULL, "no file matches the pattern"},
        {"un/b_{}.f32", "--start=11", "is in the frame range given"},
        {"dup/c_{}.f32 un/b_1.f32", NULL, "must be the only input"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char first[PATH_CAP];
        snprintf(first, sizeof first, "%s", cases[i].input);
        char *second = strchr(first, ' ');
        if (second)
            *second++ = '\0';
        const char *args[12] = {"render", path_in(env, first, in), "-o", path_in(env, "never.mp4", out),
                                "--server", "127.0.0.1:1", "--up", "z"};
        int n = 8;
        char other[PATH_CAP];
        if (second)
            args[n++] = path_in(env, second, other);
        if (cases[i].extra)
            args[n++] = cases[i].extra;
        args[n] = NULL;
        cli_result r;
        cli_run(FLUIDCAST_CLI_PATH, env->dir, args, &r);
        CHECK_MSG(r.status == 2 && strstr(r.err, cases[i].message), "%s: exit %d, expected \"%s\" in\n%s%s",
                  cases[i].input, r.status, cases[i].message, r.out, r.err);
    }
}

static void expect_usage(const test_env *env, const char *out, const char *const *extra, const char *message)
{
    char in[PATH_CAP], path[PATH_CAP];
    cli_result r;
    render(env, (const char *const[]){pattern_input(env, in), NULL}, path_in(env, out, path), extra, &r);
    CHECK_MSG(r.status == 2 && strstr(r.err, message), "%s: exit %d: %s", message, r.status, r.err);
}

static void test_usage_errors(const test_env *env)
{
    expect_usage(env, "x.mp4", (const char *const[]){"--skip-existing", NULL}, "--skip-existing resumes image");
    expect_usage(env, "x.mp4", (const char *const[]){"--size", "161x120", NULL}, "even width and height");
    expect_usage(env, "x.mp4", (const char *const[]){"--quality", "52", NULL}, "0..51");
    expect_usage(env, "x.png", NULL, "image pattern with one %d");
    expect_usage(env, "x_%d.png", (const char *const[]){"--bogus", NULL}, "unknown option --bogus");
}

static void remove_tree(const char *dir)
{
    char command[PATH_CAP + 16];
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    if (system(command) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
}

/* A sequence coloured by speed without --range gets one range for all its
 * frames from the first frame's speeds (2nd-98th percentile), printed before
 * the connection is made; with --range nothing is chosen. The first frame's
 * 100 particles move at 1..100 (particle i at i + 1), so the range is near 3:98. */
static void test_color_range_from_the_first_frame(const test_env *env)
{
    char path[PATH_CAP], out[PATH_CAP];
    FILE *f = fopen(path_in(env, "in/moving.csv", path), "w");
    CHECK(f != NULL);
    if (!f)
        return;
    fputs("x,y,z,vx,vy,vz\n", f);
    for (int i = 0; i < 100; i++)
        fprintf(f, "%d,%d,0,%d,0,0\n", i % 10, i / 10, i + 1);
    CHECK(fclose(f) == 0);
    const char *chosen[] = {"render", path, "-o", path_in(env, "never.mp4", out), "--server", "127.0.0.1:1",
                            "--up", "z", "--color-by", "speed", NULL};
    cli_result r;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, chosen, &r);
    double lo = 0, hi = 0;
    const char *line = strstr(r.out, "color range: speed ");
    CHECK_MSG(r.status == 4 && line && sscanf(line, "color range: speed %lf:%lf", &lo, &hi) == 2,
              "exit %d:\n%s%s", r.status, r.out, r.err);
    CHECK_MSG(lo >= 2.0 && lo <= 4.0 && hi >= 97.0 && hi <= 99.0, "range %g:%g", lo, hi);
    const char *given[] = {"render", path, "-o", out, "--server", "127.0.0.1:1", "--up", "z", "--color-by", "speed",
                           "--range", "0:10", NULL};
    cli_run(FLUIDCAST_CLI_PATH, env->dir, given, &r);
    CHECK_MSG(r.status == 4 && !strstr(r.out, "color range:"), "exit %d:\n%s", r.status, r.out);
}

int main(void)
{
    test_env env = {.dir = "/tmp/fluidcast-cli-render-XXXXXX"};
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
    test_usage_errors(&env);
    test_input_order(&env);
    test_brace_pattern_errors(&env);
    test_color_range_from_the_first_frame(&env);
    double centroid[FRAMES];
    test_png_sequence(&env, centroid);
    test_videos(&env, centroid);
    test_skip_existing(&env);
    test_missing_and_corrupt_frames(&env);
    test_interrupt(&env);
    test_orbit(&env);
    test_per_frame_mesh(&env);
    test_mesh_transforms(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    if (getenv("FLUIDCAST_TEST_KEEP"))   /* to look at the images and videos */
        printf("kept %s\n", env.dir);
    else
        remove_tree(env.dir);
    return test_result();
}
