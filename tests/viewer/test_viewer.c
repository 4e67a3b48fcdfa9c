/* test_viewer.c — `fluidcast view` in an X server (run under xvfb-run by
 * CTest) against the real daemon, driven through its --test-script hook:
 *   draw        the first image is drawn: the window's centre shows the
 *               fluid (blue), its corners the floor and sky (grey)
 *   drag        a left drag of 80 px in a 240 px high window turns the eye
 *               about the pivot by -80/240*pi about up (the scene's front
 *               to the right), the picture changes, and the p key writes a
 *               full-size PNG
 *   pick        a double-click at the window's centre makes the fluid's front
 *               surface on the view axis the pivot: the view recentres on it
 *               (eye and target move together); one in a corner (floor, no
 *               fluid) leaves the camera alone
 *   spacemouse  under umockdev-run with tests/input's Compact holding +X:
 *               the camera pans (its target moves against the view's right)
 *   quality     several drags 100 ms apart: the images shown while moving
 *               are the half-size previews (160x120), and once the camera has
 *               been still the last image is the full 320x240 one
 *   resize      `resize 400 300`: once the resize settles the daemon renders
 *               at the new size and the image shown is 400x300, not a preview
 *   playback    three files, the slab shifted by SHIFT along y and z from one
 *               to the next: the sequence plays (several frames shown), space
 *               pauses it, each n shows the next file (frame index + 1, mod 3)
 *               and the fluid's centre in the window moves by about the same
 *               step from file 0 to 1 as from 1 to 2
 *   h264        the slab published to a session (by this test, through
 *               libfluidcast); `view --session --format h264` decodes the
 *               daemon's H.264 stream and draws it as `draw` requires
 *   session_end `view --session` before any producer: it says (stderr and
 *               title) that it waits for the session; the slab is published
 *               and drawn; the producer leaves: the viewer says the session
 *               ended, and a drag after that still shows a new picture of the
 *               last frame (PROTOCOL.md 10.1), the title saying so
 *   session_drag the slab published to a session whose producer stays but
 *               sends nothing more (a slow simulation between frames): a drag
 *               in `view --session` (raw images, which have no lossless
 *               refresh to wake the viewer) is rendered and shown at once,
 *               not at the producer's next frame
 * Usage: test_viewer MODE FLUIDCAST_CLI TESTS_INPUT_DIR [GALLERY_PNG] */
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "support/tinted_look.h"
#include "test_util.h"

/* A check the rest of the test depends on: failing, it ends the test. */
#define REQUIRE_MSG(cond, ...)          \
    do {                                \
        if (!(cond)) {                  \
            CHECK_MSG(cond, __VA_ARGS__); \
            return 1;                   \
        }                               \
    } while (0)
#define REQUIRE(cond) REQUIRE_MSG(cond, "%s", "")

extern char **environ;

#define WIDTH 320
#define HEIGHT 240
#define DRAG_PX 80
#define RESIZED_W 400
#define RESIZED_H 300
#define FILES 3
#define SHIFT 0.12f

/* A slab of particles, long along x, so that turning it changes its picture:
 * its positions into p (NULL: only counted); returns the count. */
static uint64_t slab_points(float *p, float shift)
{
    const float s = 0.0625f;
    uint64_t n = 0;
    for (int i = -12; i <= 12; i++)
        for (int j = -4; j <= 4; j++)
            for (int k = -4; k <= 4; k++)
                if (i * i / 144.0 + j * j / 16.0 + k * k / 16.0 <= 1.0) {
                    if (p) {
                        p[3 * n] = i * s;
                        p[3 * n + 1] = j * s + shift;
                        p[3 * n + 2] = k * s + shift;
                    }
                    n++;
                }
    return n;
}

static bool write_slab(const char *path, float shift)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    fc_frame frame = {0};
    fc_error err;
    bool ok = fc_frame_alloc(&frame, slab_points(NULL, 0), 0, &err) == FC_OK;
    if (ok) {
        slab_points(frame.positions, shift);
        ok = fwrite(frame.positions, 12, frame.count, f) == frame.count;
    }
    fc_frame_free(&frame);
    return fclose(f) == 0 && ok;
}

/* A producer holding the slab as session `name`'s frame (NULL on failure). */
static fc_client *publish_slab(const char *server, const char *name)
{
    fc_connect_options options = {.client_name = "test_viewer producer", .reply_timeout_ms = 30000};
    fc_client *c = NULL;
    fc_frame frame = {0};
    fc_error err;
    bool ok = fc_client_connect(server, &options, &c, &err) == FC_OK &&
              fc_client_publish(c, name, NULL, &err) == FC_OK &&
              fc_frame_alloc(&frame, slab_points(NULL, 0), 0, &err) == FC_OK;
    if (ok) {
        slab_points(frame.positions, 0);
        ok = fc_client_send_frame(c, &frame, &err) == FC_OK;
    }
    fc_frame_free(&frame);
    if (!ok) {
        fprintf(stderr, "producer: %s\n", err.message);
        fc_client_close(c);
        return NULL;
    }
    return c;
}

/* Runs argv with stdout and stderr to out_path; the exit status or -1. */
static int run(const char *const *argv, const char *out_path)
{
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid;
    int status = 0, result = -1;
    if (posix_spawnp(&pid, argv[0], &actions, NULL, (char *const *)argv, environ) == 0 &&
        waitpid(pid, &status, 0) == pid && WIFEXITED(status))
        result = WEXITSTATUS(status);
    posix_spawn_file_actions_destroy(&actions);
    return result;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = malloc((size_t)n + 1);
    if (text && fread(text, 1, (size_t)n, f) != (size_t)n)
        n = 0;
    if (text)
        text[n] = '\0';
    fclose(f);
    return text;
}

typedef struct logged_camera {
    float eye[3], target[3], up[3];
    unsigned width, height;
    bool preview;
} logged_camera;

/* The last full-size camera logged before `before` (NULL: the end), or the first one (first true). */
static bool find_camera(const char *log, const char *before, bool first, logged_camera *out)
{
    bool found = false;
    for (const char *p = strstr(log, "camera "); p && (!before || p < before); p = strstr(p + 1, "\ncamera ")) {
        if (*p == '\n')
            p++;
        logged_camera c = {0};
        const char *eol = strchr(p, '\n');
        const char *tag = strstr(p, "preview");
        c.preview = tag && (!eol || tag < eol);
        if (sscanf(p, "camera %*u: eye %f %f %f target %f %f %f up %f %f %f size %ux%u", &c.eye[0], &c.eye[1],
                   &c.eye[2], &c.target[0], &c.target[1], &c.target[2], &c.up[0], &c.up[1], &c.up[2], &c.width,
                   &c.height) == 11 &&
            !c.preview) {
            *out = c;
            found = true;
            if (first)
                return true;
        }
    }
    return found;
}

static bool decode_bmp(const char *path, fc_decoded_image *img)
{
    size_t size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    fseek(f, 0, SEEK_END);
    size = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *data = malloc(size);
    bool ok = data && fread(data, 1, size, f) == size;
    fclose(f);
    fc_error err;
    ok = ok && fc_decode_image(data, size, "bmp", 0, img, &err) == FC_OK;
    if (!ok)
        fprintf(stderr, "%s: cannot decode\n", path);
    free(data);
    return ok;
}

/* Mean blue-minus-red over a square of side `side` at (x0, y0): the fluid is
 * blue, the floor and sky grey. */
static double blueness(const fc_decoded_image *img, int x0, int y0, int side)
{
    double sum = 0;
    const uint8_t *px = img->pixels;
    for (int y = y0; y < y0 + side; y++)
        for (int x = x0; x < x0 + side; x++) {
            const uint8_t *p = px + ((size_t)y * img->width + x) * img->channels;
            sum += (double)p[2] - (double)p[0];
        }
    return sum / (side * side);
}

static double mean_abs_difference(const fc_decoded_image *a, const fc_decoded_image *b)
{
    double sum = 0;
    size_t n = (size_t)a->width * a->height * a->channels;
    for (size_t i = 0; i < n; i++)
        sum += fabs((double)((uint8_t *)a->pixels)[i] - (double)((uint8_t *)b->pixels)[i]);
    return sum / (double)n;
}

/* The mean absolute difference of two window shots (BMP files), -1 when one
 * cannot be read. */
static double shots_difference(const char *before, const char *after)
{
    fc_decoded_image a = {0}, b = {0};
    double diff = decode_bmp(before, &a) && decode_bmp(after, &b) ? mean_abs_difference(&a, &b) : -1.0;
    fc_decoded_image_free(&a);
    fc_decoded_image_free(&b);
    return diff;
}

typedef struct scene {
    char dir[64];
    char slab[128];
    char more[FILES - 1][128];    /* playback: the slab shifted once, twice */
    char server[32];
    const char *cli;
    const char *input_dir;
    const char *gallery;
} scene;

static int test_draw(const scene *s, const char *log, const char *shot)
{
    REQUIRE_MSG(strstr(log, "shot: ") != NULL, "no screenshot taken:\n%s", log);
    fc_decoded_image img = {0};
    REQUIRE(decode_bmp(shot, &img));
    REQUIRE(img.width == WIDTH && img.height == HEIGHT);
    double centre = blueness(&img, WIDTH / 2 - 10, HEIGHT / 2 - 10, 20);
    double corners = (blueness(&img, 0, 0, 10) + blueness(&img, WIDTH - 10, 0, 10) +
                      blueness(&img, 0, HEIGHT - 10, 10) + blueness(&img, WIDTH - 10, HEIGHT - 10, 10)) / 4;
    printf("draw: blue - red at the centre %.1f, at the corners %.1f\n", centre, corners);
    REQUIRE_MSG(centre > corners + 40.0, "the centre (%.1f) is not the fluid against the corners (%.1f)", centre,
              corners);
    fc_decoded_image_free(&img);
    if (s->gallery) {
        const char *argv[] = {"oiiotool", shot, "-o", s->gallery, NULL};
        char out[160];
        snprintf(out, sizeof out, "%s/oiiotool.out", s->dir);
        if (run(argv, out) == 0)
            printf("gallery: %s\n", s->gallery);
    }
    return 0;
}

/* Angle of v's projection on the plane normal to up, about up. */
static double azimuth(const float v[3], const float up[3])
{
    /* a basis of the plane: any vector not along up, made normal to it */
    double a[3] = {fabsf(up[0]) < 0.9f ? 1 : 0, fabsf(up[0]) < 0.9f ? 0 : 1, 0};
    double d = a[0] * up[0] + a[1] * up[1] + a[2] * up[2];
    for (int i = 0; i < 3; i++)
        a[i] -= d * up[i];
    double b[3] = {up[1] * a[2] - up[2] * a[1], up[2] * a[0] - up[0] * a[2], up[0] * a[1] - up[1] * a[0]};
    return atan2(v[0] * b[0] + v[1] * b[1] + v[2] * b[2], v[0] * a[0] + v[1] * a[1] + v[2] * a[2]);
}

/* session_drag: an image answering a camera request (generation > 1) is shown
 * before the second shot, with the session still live, and it differs. */
static int test_session_drag(const char *log, const char *before, const char *after)
{
    const char *second_shot = strstr(log, "shot: ");
    second_shot = second_shot ? strstr(second_shot + 1, "shot: ") : NULL;
    REQUIRE_MSG(second_shot != NULL, "two screenshots expected:\n%s", log);
    REQUIRE_MSG(strstr(log, "ended") == NULL, "the session ended; it should have stayed live:\n%s", log);
    unsigned long long generation = 0;
    for (const char *p = strstr(log, "shown "); p && p < second_shot; p = strstr(p + 1, "shown "))
        generation = strtoull(p + 6, NULL, 10);
    CHECK_MSG(generation > 1, "the image shown after the drag answers request %llu:\n%s", generation, log);
    double diff = shots_difference(before, after);
    REQUIRE(diff >= 0.0);
    printf("session_drag: mean absolute difference of the pictures before and after the drag %.1f\n", diff);
    CHECK(diff > 5.0);
    return 0;
}

static int test_drag(const scene *s, const char *log, const char *before, const char *after)
{
    const char *second_shot = strstr(log, "shot: ");
    second_shot = second_shot ? strstr(second_shot + 1, "shot: ") : NULL;
    REQUIRE_MSG(second_shot != NULL, "two screenshots expected:\n%s", log);
    logged_camera c0, c1;
    REQUIRE(find_camera(log, NULL, true, &c0));
    REQUIRE(find_camera(log, second_shot, false, &c1));
    float o0[3], o1[3];
    for (int i = 0; i < 3; i++)
        o0[i] = c0.eye[i] - c0.target[i], o1[i] = c1.eye[i] - c1.target[i];
    double turn = azimuth(o1, c0.up) - azimuth(o0, c0.up);
    turn = remainder(turn, 2 * M_PI);
    double expected = -(double)DRAG_PX / HEIGHT * M_PI;
    printf("drag: the eye turned %.4f rad about up (expected %.4f)\n", turn, expected);
    CHECK_NEAR(turn, expected, 0.01);
    CHECK_NEAR(sqrt(o0[0] * o0[0] + o0[1] * o0[1] + o0[2] * o0[2]),
               sqrt(o1[0] * o1[0] + o1[1] * o1[1] + o1[2] * o1[2]), 1e-3);
    REQUIRE(c1.width == WIDTH && c1.height == HEIGHT);
    REQUIRE_MSG(strstr(log, "preview") != NULL, "no half-size preview while dragging:\n%s", log);
    double diff = shots_difference(before, after);
    REQUIRE(diff >= 0.0);
    printf("drag: mean absolute difference of the pictures %.1f\n", diff);
    REQUIRE(diff > 5.0);
    char png[128];
    snprintf(png, sizeof png, "%s/fluidcast-view-0001.png", s->dir);
    REQUIRE_MSG(access(png, R_OK) == 0, "p wrote no %s", png);
    return 0;
}

static int test_spacemouse(const char *log)
{
    logged_camera c0, c1;
    REQUIRE_MSG(strstr(log, "SpaceMouse: SpaceMouse Compact") != NULL, "no SpaceMouse found:\n%.2000s", log);
    REQUIRE(find_camera(log, NULL, true, &c0));
    /* the last camera sent, preview or not */
    const char *last = NULL;
    for (const char *p = strstr(log, "camera "); p; p = strstr(p + 1, "\ncamera "))
        last = *p == '\n' ? p + 1 : p;
    REQUIRE(last && sscanf(last, "camera %*u: eye %f %f %f target %f %f %f", &c1.eye[0], &c1.eye[1], &c1.eye[2],
                         &c1.target[0], &c1.target[1], &c1.target[2]) == 6);
    /* +X held: the scene moves right, so the pivot moves along -right */
    double f[3], right[3], moved = 0;
    for (int i = 0; i < 3; i++)
        f[i] = c0.target[i] - c0.eye[i];
    right[0] = f[1] * c0.up[2] - f[2] * c0.up[1];
    right[1] = f[2] * c0.up[0] - f[0] * c0.up[2];
    right[2] = f[0] * c0.up[1] - f[1] * c0.up[0];
    double n = sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
    for (int i = 0; i < 3; i++)
        moved += (c1.target[i] - c0.target[i]) * right[i] / n;
    printf("spacemouse: the pivot moved %.3f along the view's right\n", moved);
    REQUIRE(moved < -0.05);
    return 0;
}

static double distance(const float a[3], const float b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static int test_pick(const char *log)
{
    const char *p1 = strstr(log, "pick 1: fluid at ");
    const char *p2 = strstr(log, "pick 2: no fluid");
    REQUIRE_MSG(p1 && p2, "expected a pick on the fluid, then one off it:\n%s", log);
    float pivot[3];
    REQUIRE(sscanf(p1, "pick 1: fluid at %f %f %f", &pivot[0], &pivot[1], &pivot[2]) == 3);
    logged_camera c0, c1, c2;
    REQUIRE(find_camera(log, NULL, true, &c0));
    REQUIRE(find_camera(log, p2, false, &c1));
    REQUIRE(find_camera(log, NULL, false, &c2));
    /* on the view axis, in front of the centre by less than the slab's half-length (0.75; its surface
     * along this axis is about 0.29 + a particle radius in front) */
    double to_centre = distance(c0.eye, c0.target), to_pivot = distance(c0.eye, pivot);
    double off_axis = distance(pivot, c0.target) - (to_centre - to_pivot);
    printf("pick: pivot %.3f from the eye (centre %.3f), %.4f off the axis\n", to_pivot, to_centre, off_axis);
    CHECK(to_pivot < to_centre - 0.1 && to_pivot > to_centre - 0.5);
    CHECK_NEAR(off_axis, 0.0, 0.02);
    /* recentred: the target is the pivot, the eye moved with it */
    CHECK_NEAR(distance(c1.target, pivot), 0.0, 1e-4);
    for (int i = 0; i < 3; i++)
        CHECK_NEAR(c1.eye[i] - c1.target[i], c0.eye[i] - c0.target[i], 1e-4);
    CHECK_NEAR(distance(c2.target, c1.target) + distance(c2.eye, c1.eye), 0.0, 1e-6);
    return 0;
}


typedef struct shown_image {
    unsigned width, height, frame;
    bool preview;
    const char *at;               /* where its line starts in the log */
} shown_image;

/* The images the viewer showed ("shown G: WxH frame I[ preview]" lines), in order; their count. */
static int find_shown(const char *log, shown_image *out, int max)
{
    int n = 0;
    for (const char *p = strstr(log, "shown "); p && n < max; p = strstr(p + 1, "\nshown ")) {
        if (*p == '\n')
            p++;
        shown_image s = {.at = p};
        const char *eol = strchr(p, '\n');
        const char *tag = strstr(p, " preview");
        s.preview = tag && (!eol || tag < eol);
        if (sscanf(p, "shown %*u: %ux%u frame %u", &s.width, &s.height, &s.frame) == 3)
            out[n++] = s;
    }
    return n;
}

#define MAX_SHOWN 512

static int test_quality(const char *log)
{
    static shown_image shown[MAX_SHOWN];
    int n = find_shown(log, shown, MAX_SHOWN);
    REQUIRE_MSG(n >= 3, "expected a full image, previews, a full image:\n%s", log);
    REQUIRE_MSG(!shown[0].preview && shown[0].width == WIDTH && shown[0].height == HEIGHT,
                "the first image is %ux%u%s, not the full %dx%d", shown[0].width, shown[0].height,
                shown[0].preview ? " preview" : "", WIDTH, HEIGHT);
    int previews = 0;
    for (int i = 0; i < n; i++)
        if (shown[i].preview) {
            previews++;
            CHECK_MSG(shown[i].width == WIDTH / 2 && shown[i].height == HEIGHT / 2,
                      "a preview of %ux%u, not the halved %dx%d", shown[i].width, shown[i].height, WIDTH / 2,
                      HEIGHT / 2);
        }
    const shown_image *last = &shown[n - 1];
    printf("quality: %d images shown, %d of them previews; the last %ux%u%s\n", n, previews, last->width,
           last->height, last->preview ? " preview" : "");
    REQUIRE_MSG(previews > 0, "no preview shown while dragging:\n%s", log);
    REQUIRE_MSG(!last->preview && last->width == WIDTH && last->height == HEIGHT,
                "at rest the last image is %ux%u%s, not the full %dx%d", last->width, last->height,
                last->preview ? " preview" : "", WIDTH, HEIGHT);
    return 0;
}

static int test_resize(const char *log)
{
    static shown_image shown[MAX_SHOWN];
    int n = find_shown(log, shown, MAX_SHOWN);
    REQUIRE_MSG(n >= 2, "expected an image before and after the resize:\n%s", log);
    REQUIRE(shown[0].width == WIDTH && shown[0].height == HEIGHT);
    const shown_image *last = &shown[n - 1];
    printf("resize: the last image %ux%u%s (window %dx%d)\n", last->width, last->height,
           last->preview ? " preview" : "", RESIZED_W, RESIZED_H);
    REQUIRE_MSG(!last->preview && last->width == RESIZED_W && last->height == RESIZED_H,
                "after the resize the image is %ux%u%s, not %dx%d:\n%s", last->width, last->height,
                last->preview ? " preview" : "", RESIZED_W, RESIZED_H, log);
    logged_camera c;
    REQUIRE(find_camera(log, NULL, false, &c));
    CHECK(c.width == RESIZED_W && c.height == RESIZED_H);
    const char *shot = strstr(log, "shot: ");
    int w = 0, h = 0;
    REQUIRE(shot && sscanf(strstr(shot, "("), "(%dx%d)", &w, &h) == 2);
    CHECK(w == RESIZED_W && h == RESIZED_H);
    return 0;
}

/* Centre of the fluid's (blue) pixels in a screenshot; false when there are none. */
static bool fluid_centre(const char *bmp, double centre[2])
{
    fc_decoded_image img = {0};
    if (!decode_bmp(bmp, &img))
        return false;
    double sx = 0, sy = 0, count = 0;
    const uint8_t *px = img.pixels;
    for (uint32_t y = 0; y < img.height; y++)
        for (uint32_t x = 0; x < img.width; x++) {
            const uint8_t *p = px + ((size_t)y * img.width + x) * img.channels;
            if ((int)p[2] - (int)p[0] > 40)
                sx += x, sy += y, count++;
        }
    fc_decoded_image_free(&img);
    if (count < 20)
        return false;
    centre[0] = sx / count;
    centre[1] = sy / count;
    return true;
}

static int test_playback(const scene *s, const char *log)
{
    static shown_image shown[MAX_SHOWN];
    int n = find_shown(log, shown, MAX_SHOWN);
    const char *pause = strstr(log, "shot: ");
    REQUIRE_MSG(pause != NULL, "no screenshots:\n%s", log);
    /* playing: before the first shot (after the pause) more than one file was shown */
    bool seen[FILES] = {false};
    int distinct = 0;
    for (int i = 0; i < n && shown[i].at < pause; i++)
        if (shown[i].frame < FILES && !seen[shown[i].frame])
            seen[shown[i].frame] = true, distinct++;
    printf("playback: %d of %d files shown while playing\n", distinct, FILES);
    CHECK_MSG(distinct >= 2, "the sequence did not play:\n%s", log);
    /* each shot: the frame of the last image shown before it */
    double centre[FILES][2];
    bool have[FILES] = {false};
    int previous = -1;
    const char *shot = pause;
    for (int k = 0; k < FILES; k++, shot = strstr(shot + 1, "shot: ")) {
        REQUIRE_MSG(shot != NULL, "%d screenshots expected:\n%s", FILES, log);
        int frame = -1;
        for (int i = 0; i < n && shown[i].at < shot; i++)
            frame = (int)shown[i].frame;
        REQUIRE(frame >= 0 && frame < FILES);
        if (previous >= 0)
            CHECK_MSG(frame == (previous + 1) % FILES, "n stepped from file %d to %d", previous, frame);
        previous = frame;
        char bmp[128];
        snprintf(bmp, sizeof bmp, "%s/step%d.bmp", s->dir, k);
        REQUIRE_MSG(fluid_centre(bmp, centre[frame]), "no fluid in %s", bmp);
        have[frame] = true;
        printf("playback: shot %d shows file %d, the fluid's centre at %.1f, %.1f\n", k, frame, centre[frame][0],
               centre[frame][1]);
    }
    REQUIRE_MSG(have[0] && have[1] && have[2], "the steps did not show every file");
    double d01[2] = {centre[1][0] - centre[0][0], centre[1][1] - centre[0][1]};
    double d12[2] = {centre[2][0] - centre[1][0], centre[2][1] - centre[1][1]};
    double l01 = hypot(d01[0], d01[1]), l12 = hypot(d12[0], d12[1]);
    double cosine = (d01[0] * d12[0] + d01[1] * d12[1]) / (l01 * l12 + 1e-9);
    printf("playback: the centre moved %.1f px from file 0 to 1, %.1f px from 1 to 2 (cosine %.3f)\n", l01, l12,
           cosine);
    CHECK(l01 > 5.0 && l12 > 5.0);
    CHECK(cosine > 0.9);
    CHECK(l12 > 0.5 * l01 && l12 < 2.0 * l01);
    return 0;
}

/* `wait 2` with no image ever coming: the viewer gives up after its limit,
 * not the test's, with exit status 7 and what it waited for. */
static int test_wait_limit(int status, double took_ms, const char *log)
{
    REQUIRE(log != NULL);
    printf("wait_limit: exit status %d after %.0f ms:\n%s", status, took_ms, log);
    CHECK_MSG(status == 7, "exit status %d, 7 expected", status);
    CHECK(strstr(log, "wait: no image at rest after 2 s") != NULL);
    CHECK(strstr(log, "no image yet") != NULL);
    /* Not before its 2 s; that it was its own limit, not the test's, the message and status say. */
    CHECK_MSG(took_ms >= 2000.0, "gave up after %.0f ms", took_ms);
    return 0;
}

/* session_end's producer: publishes the slab once the viewer says it waits,
 * and leaves once the viewer has shown it. */
typedef struct ending_producer {
    const char *server;
    const char *out_path;          /* the viewer's log */
    bool ok;
} ending_producer;

/* Waits (bounded: 60 s) until the viewer's log holds `text`. */
static bool log_shows(const char *path, const char *text)
{
    for (int tries = 0; tries < 3000; tries++) {
        char *log = read_text(path);
        bool found = log && strstr(log, text);
        free(log);
        if (found)
            return true;
        nanosleep(&(struct timespec){0, 20000000L}, NULL);
    }
    fprintf(stderr, "producer: the viewer never logged \"%s\"\n", text);
    return false;
}

static void *run_ending_producer(void *arg)
{
    ending_producer *p = arg;
    if (!log_shows(p->out_path, "waiting for session view-end"))
        return NULL;
    fc_client *c = publish_slab(p->server, "view-end");
    fc_error err;
    p->ok = c && log_shows(p->out_path, "shown ") && fc_client_leave_session(c, &err) == FC_OK;
    fc_client_close(c);
    return NULL;
}

/* The order of the viewer's words: waiting, the slab, the end, then the drag's picture, which differs. */
static int test_session_end(const char *log, const char *before, const char *after)
{
    const char *waiting = strstr(log, "fluidcast: waiting for session view-end");
    const char *waiting_title = strstr(log, "title: fluidcast view | waiting for session view-end");
    const char *first = strstr(log, "shown ");
    const char *ended = strstr(log, "fluidcast: session view-end ended; drag to look around, q quits");
    const char *ended_title = strstr(log, "session view-end ended, frame 1: drag to look around, q quits");
    REQUIRE_MSG(waiting && waiting_title && first && waiting < first && waiting_title < first,
                "no waiting message before the first image:\n%s", log);
    REQUIRE_MSG(ended && ended > first && ended_title, "no word of the end after the first image:\n%s", log);
    const char *second_shot = strstr(log, "shot: ");
    second_shot = second_shot ? strstr(second_shot + 1, "shot: ") : NULL;
    REQUIRE_MSG(second_shot && second_shot > ended, "no screenshot after the end:\n%s", log);
    /* The picture after the end answers the drag (a camera request newer than the first). */
    const char *last_shown = NULL;
    for (const char *p = strstr(ended, "shown "); p && p < second_shot; p = strstr(p + 1, "shown "))
        last_shown = p;
    REQUIRE_MSG(last_shown != NULL, "no image shown after the end:\n%s", log);
    unsigned long long generation = strtoull(last_shown + 6, NULL, 10);
    CHECK_MSG(generation > 1, "the image after the end answers request %llu", generation);
    double diff = shots_difference(before, after);
    REQUIRE(diff >= 0.0);
    printf("session_end: mean absolute difference of the pictures before and after the drag %.1f\n", diff);
    CHECK(diff > 5.0);
    return 0;
}

static int run_viewer(const scene *s, const char *mode, char **log)
{
    char script[512], a[128], b[128], out[128];
    snprintf(a, sizeof a, "%s/before.bmp", s->dir);
    snprintf(b, sizeof b, "%s/after.bmp", s->dir);
    snprintf(out, sizeof out, "%s/view.out", s->dir);
    const char *argv[32];
    int n = 0;
    char ioctl[256], device[256];
    if (strcmp(mode, "spacemouse") == 0) {
        snprintf(device, sizeof device, "%s/compact.umockdev", s->input_dir);
        snprintf(ioctl, sizeof ioctl, "/dev/bus/usb/001/005=%s/compact_hold.ioctl", s->input_dir);
        const char *pre[] = {"umockdev-run", "--device", device, "--ioctl", ioctl, "--"};
        for (size_t i = 0; i < sizeof pre / sizeof pre[0]; i++)
            argv[n++] = pre[i];
        snprintf(script, sizeof script, "sleep 1500; quit");
    } else if (strcmp(mode, "pick") == 0) {
        snprintf(script, sizeof script, "wait; dclick 0 0; wait; dclick %d %d; wait; quit", -WIDTH / 2 + 4,
                 HEIGHT / 2 - 4);
    } else if (strcmp(mode, "quality") == 0) {
        /* each drag restarts the 300 ms still timer: the camera moves for about half a second */
        snprintf(script, sizeof script,
                 "wait; drag 20 0; sleep 120; drag 20 0; sleep 120; drag 20 0; sleep 120; drag 20 0; wait; quit");
    } else if (strcmp(mode, "resize") == 0) {
        /* the sleep lets the window's SIZE_CHANGED event arrive before `wait` looks */
        snprintf(script, sizeof script, "wait; resize %d %d; sleep 400; wait; shot %s; quit", RESIZED_W, RESIZED_H,
                 a);
    } else if (strcmp(mode, "playback") == 0) {
        snprintf(script, sizeof script,
                 "wait; sleep 800; key space; sleep 200; wait; shot %s/step0.bmp; key n; wait; shot %s/step1.bmp; "
                 "key n; wait; shot %s/step2.bmp; quit",
                 s->dir, s->dir, s->dir);
    } else if (strcmp(mode, "wait_limit") == 0) {
        snprintf(script, sizeof script, "wait 2; quit");
    } else if (strcmp(mode, "session_end") == 0) {
        /* The drag's picture can only come after the end: no frame follows the first. */
        snprintf(script, sizeof script, "wait; shot %s; sleep 500; drag %d 0; wait; shot %s; quit", a, DRAG_PX, b);
    } else if (strcmp(mode, "session_drag") == 0) {
        snprintf(script, sizeof script, "wait; shot %s; drag %d 0; wait; shot %s; quit", a, DRAG_PX, b);
    } else if (strcmp(mode, "draw") == 0 || strcmp(mode, "h264") == 0) {
        snprintf(script, sizeof script, "wait; shot %s; quit", a);
    } else {
        snprintf(script, sizeof script, "wait; shot %s; drag %d 0; wait; shot %s; key p; wait; quit", a, DRAG_PX, b);
    }
    char size[32];
    snprintf(size, sizeof size, "%dx%d", WIDTH, HEIGHT);
    bool h264 = strcmp(mode, "h264") == 0;
    const char *rest[] = {s->cli, "view", s->slab, "--server", s->server, "--size", size, "--log-camera",
                          "--absorption", TINTED_LOOK_ABSORPTION, "--test-script", script};
    for (size_t i = 0; i < sizeof rest / sizeof rest[0]; i++)
        argv[n++] = rest[i];
    fc_client *producer = NULL;
    if (h264) {
        /* The session's frame is there before the viewer subscribes: its first image is that frame's IDR. */
        producer = publish_slab(s->server, "view-h264");
        REQUIRE(producer != NULL);
        argv[2] = "--session=view-h264";   /* in place of the files */
        argv[n++] = "--format";
        argv[n++] = "h264";
    }
    if (strcmp(mode, "session_drag") == 0) {
        producer = publish_slab(s->server, "view-live");   /* stays, publishing nothing more */
        REQUIRE(producer != NULL);
        argv[2] = "--session=view-live";
    }
    if (strcmp(mode, "wait_limit") == 0)
        argv[2] = "--session=nobody-publishes";   /* a session no producer ever fills: no image comes */
    ending_producer ending = {.server = s->server, .out_path = out};
    pthread_t ending_thread;
    bool session_end = strcmp(mode, "session_end") == 0;
    if (session_end) {
        argv[2] = "--session=view-end";
        REQUIRE(pthread_create(&ending_thread, NULL, run_ending_producer, &ending) == 0);
    }
    if (strcmp(mode, "playback") == 0)
        for (int i = 1; i < FILES; i++)
            argv[n++] = s->more[i - 1];
    if (strcmp(mode, "spacemouse") != 0)
        argv[n++] = "--no-spacemouse";
    argv[n] = NULL;
    double started = now_ms();
    int status = run(argv, out);
    double took = now_ms() - started;
    fc_client_close(producer);
    if (session_end)
        pthread_join(ending_thread, NULL);
    *log = read_text(out);
    if (strcmp(mode, "wait_limit") == 0)
        return test_wait_limit(status, took, *log);
    REQUIRE_MSG(status == 0 && *log, "the viewer exited with %d:\n%s", status, *log ? *log : "");
    if (strcmp(mode, "draw") == 0 || h264)
        return test_draw(s, *log, a);
    if (strcmp(mode, "drag") == 0)
        return test_drag(s, *log, a, b);
    if (strcmp(mode, "session_drag") == 0)
        return test_session_drag(*log, a, b);
    if (strcmp(mode, "pick") == 0)
        return test_pick(*log);
    if (strcmp(mode, "quality") == 0)
        return test_quality(*log);
    if (strcmp(mode, "resize") == 0)
        return test_resize(*log);
    if (strcmp(mode, "playback") == 0)
        return test_playback(s, *log);
    if (session_end) {
        CHECK_MSG(ending.ok, "the producer did not publish and leave");
        return test_session_end(*log, a, b);
    }
    return test_spacemouse(*log);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: test_viewer draw|drag|pick|spacemouse|h264|quality|resize|playback|wait_limit|session_end|session_drag FLUIDCAST_CLI TESTS_INPUT_DIR [GALLERY_PNG]\n");
        return 2;
    }
    const char *mode = argv[1];
    if (strcmp(mode, "spacemouse") == 0 && system("command -v umockdev-run >/dev/null 2>&1") != 0) {
        printf("umockdev-run not found (apt-get install umockdev): skipped\n");
        return 77;
    }
    scene s = {.dir = "/tmp/fc_view_XXXXXX", .cli = argv[2], .input_dir = argv[3], .gallery = argc > 4 ? argv[4] : NULL};
    REQUIRE(mkdtemp(s.dir) != NULL);
    REQUIRE(chdir(s.dir) == 0); /* the p key writes its PNG here */
    snprintf(s.slab, sizeof s.slab, "%s/slab.f32", s.dir);
    REQUIRE(write_slab(s.slab, 0));
    for (int i = 1; i < FILES; i++) {
        snprintf(s.more[i - 1], sizeof s.more[i - 1], "%s/slab%d.f32", s.dir, i);
        REQUIRE(write_slab(s.more[i - 1], SHIFT * i));
    }
    fc_test_daemon d;
    fc_error err;
    /* h264: no lossless PNG refresh, so what the window shows is the decoded H.264 picture. */
    static const char *const no_refresh[] = {"--refresh-ms", "0", NULL};
    const char *const *daemon_args = strcmp(mode, "h264") == 0 ? no_refresh : NULL;
    REQUIRE_MSG(fc_test_daemon_start(&d, daemon_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) == FC_OK, "%s",
                err.message);
    snprintf(s.server, sizeof s.server, "127.0.0.1:%u", (unsigned)d.port);
    char *log = NULL;
    int status = run_viewer(&s, mode, &log);
    free(log);
    CHECK(fc_test_daemon_stop(&d, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK);
    char cleanup[160];
    snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", s.dir);
    if (status == 0 && system(cleanup) != 0)
        fprintf(stderr, "could not remove %s\n", s.dir);
    status = status ? status : test_result();
    if (status == 0)
        printf("ok\n");
    return status;
}
