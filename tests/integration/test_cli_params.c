/* test_cli_params.c — the render parameters and scene images of `fluidcast
 * snapshot`, from the real binary through the real fluidcastd: each flag must
 * change the image the way it should (e.g. smoothing "none" or 0 iterations
 * leave the smoothed depth exactly equal to the raw depth, a density threshold
 * above every particle's density leaves no surface, a solid-colour background
 * fills the corners), bad values are usage errors (exit 2) naming the flag, and
 * images the server cannot use are its INVALID_VALUE (exit 5), as is colouring
 * by an attribute the frame lacks. Images are
 * 64x48 so every render takes a fraction of a second with software GL. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "scene_fixtures.h"
#include "support/daemon_process.h"
#include "support/image_decode.h"
#include "test_ball.h"
#include "test_util.h"

#define WIDTH 64
#define HEIGHT 48
#define PATH_SIZE 160
#define MAX_ARGS 40

typedef struct test_env {
    char dir[64];          /* scratch directory */
    char server[32];       /* HOST:PORT of the daemon */
} test_env;

static const char *scratch(const test_env *env, const char *name, char path[PATH_SIZE])
{
    snprintf(path, PATH_SIZE, "%s/%s", env->dir, name);
    return path;
}

static bool write_bytes(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    bool ok = f && fwrite(data, 1, size, f) == size;
    if (f)
        ok = fclose(f) == 0 && ok;
    return ok;
}

/* The ball with a density column (every particle 1000) and, in ballv.csv,
 * every fourth particle a fast spray droplet (density 10, moving up at 3):
 * the droplets are a minority, so the median density stays 1000. */
static bool write_csv(const fc_frame *ball, const char *path, bool with_spray)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    fputs(with_spray ? "x,y,z,density,vx,vy,vz\n" : "x,y,z,density\n", f);
    for (uint64_t i = 0; i < ball->count; i++) {
        const float *p = &ball->positions[3 * i];
        if (with_spray)
            fprintf(f, "%.9g,%.9g,%.9g,%d,0,0,3\n", (double)p[0], (double)p[1], (double)p[2], i % 4 ? 1000 : 10);
        else
            fprintf(f, "%.9g,%.9g,%.9g,1000\n", (double)p[0], (double)p[1], (double)p[2]);
    }
    return fclose(f) == 0;
}

static bool write_cube_dir(const test_env *env, const char *name, const uint8_t *face, size_t size)
{
    char dir[PATH_SIZE], path[PATH_SIZE + 16];
    scratch(env, name, dir);
    if (mkdir(dir, 0700) != 0)
        return false;
    static const char *const stems[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (int i = 0; i < 6; i++) {
        snprintf(path, sizeof path, "%s/%s.png", dir, stems[i]);
        if (!write_bytes(path, face, size))
            return false;
    }
    return true;
}

static bool write_inputs(const test_env *env)
{
    fc_frame ball = {0};
    char path[PATH_SIZE];
    bool ok = test_ball_frame(&ball, NULL) == FC_OK && test_write_f32(&ball, scratch(env, "ball.f32", path)) &&
              write_csv(&ball, scratch(env, "ball.csv", path), false) &&
              write_csv(&ball, scratch(env, "ballv.csv", path), true) &&
              write_bytes(scratch(env, "magenta.png", path), png_magenta_4x4, png_magenta_4x4_size) &&
              write_bytes(scratch(env, "rect.png", path), png_red_4x2, png_red_4x2_size) &&
              write_bytes(scratch(env, "broken.png", path), not_an_image, not_an_image_size) &&
              write_cube_dir(env, "red", png_red_4x4, png_red_4x4_size) &&
              write_cube_dir(env, "blue", png_blue_4x4, png_blue_4x4_size);
    fc_frame_free(&ball);
    return ok;
}

/* ---- running the CLI ---- */

/* Runs `fluidcast snapshot INPUT -o OUTPUT` with the test camera, the server and `extra`. */
static void run_snapshot(const test_env *env, const char *input, const char *output, const char *const *extra,
                         cli_result *r)
{
    char in[PATH_SIZE], out[PATH_SIZE];
    const char *args[MAX_ARGS] = {"snapshot", scratch(env, input, in), "-o",     scratch(env, output, out),
                                  "--server", env->server,             "--size", "64x48",
                                  "--eye",    "0,-4,0",                "--target", "0,0,0",
                                  "--radius", "0.05"};
    size_t n = 14;
    for (size_t i = 0; extra[i] && n < MAX_ARGS - 1; i++)
        args[n++] = extra[i];
    args[n] = NULL;
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, r);
}

/* Renders and decodes; a failure is a failed check and returns false. */
static bool render(const test_env *env, const char *input, const char *output, const char *const *extra,
                   fc_decoded_image *img)
{
    cli_result r;
    run_snapshot(env, input, output, extra, &r);
    CHECK_MSG(r.status == 0, "%s %s: exit %d: %s", output, extra[0] ? extra[0] : "", r.status, r.err);
    if (r.status != 0)
        return false;
    char path[PATH_SIZE];
    size_t size;
    uint8_t *data = read_whole_file(scratch(env, output, path), &size);
    const char *extension = strrchr(output, '.') + 1;
    fc_error err;
    fc_code code = data ? fc_decode_image(data, size, extension, strcmp(extension, "exr") == 0, img, &err) : FC_ERR_IO;
    CHECK_MSG(code == FC_OK, "decoding %s: %s", output, data ? err.message : "unreadable");
    free(data);
    if (code == FC_OK)
        CHECK(img->width == WIDTH && img->height == HEIGHT);
    return code == FC_OK && img->width == WIDTH && img->height == HEIGHT;
}

static size_t sample_count(const fc_decoded_image *img)
{
    return (size_t)img->width * img->height * img->channels;
}

/* Samples that differ between two images of one size and layout (all of them when the layouts differ). */
static size_t differing(const fc_decoded_image *a, const fc_decoded_image *b)
{
    if (a->channels != b->channels || a->as_float != b->as_float)
        return sample_count(a);
    size_t n = 0;
    for (size_t i = 0; i < sample_count(a); i++) {
        n += a->as_float ? ((const float *)a->pixels)[i] != ((const float *)b->pixels)[i]
                         : ((const uint8_t *)a->pixels)[i] != ((const uint8_t *)b->pixels)[i];
    }
    return n;
}

static size_t nonzero(const fc_decoded_image *img)
{
    size_t n = 0;
    for (size_t i = 0; i < sample_count(img); i++)
        n += ((const float *)img->pixels)[i] != 0.0f;
    return n;
}

static const uint8_t *pixel(const fc_decoded_image *img, uint32_t x, uint32_t y)
{
    return (const uint8_t *)img->pixels + ((size_t)y * img->width + x) * img->channels;
}

/* Renders two images of `input` that differ only in their flags; returns how
 * many samples differ (0 when a render failed, which is a failed check already). */
static size_t render_difference(const test_env *env, const char *input, const char *output,
                                const char *const *flags_a, const char *const *flags_b)
{
    char name_b[64];
    snprintf(name_b, sizeof name_b, "b-%s", output);
    fc_decoded_image a, b;
    size_t n = 0;
    if (render(env, input, output, flags_a, &a)) {
        if (render(env, input, name_b, flags_b, &b)) {
            n = differing(&a, &b);
            fc_decoded_image_free(&b);
        }
        fc_decoded_image_free(&a);
    }
    return n;
}

#define FLAGS(...) ((const char *const[]){__VA_ARGS__, NULL})
#define NO_FLAGS ((const char *const[]){NULL})

/* ---- the tests ---- */

/* The ball covers about 230 pixels of the 64x48 image. */
#define BALL_PIXELS_MIN 150

static void test_smoothing_reaches_the_server(const test_env *env)
{
    fc_decoded_image depth, none, zero, smoothed[4];
    if (!render(env, "ball.f32", "depth.exr", FLAGS("--aov", "depth"), &depth))
        return;
    CHECK_MSG(nonzero(&depth) >= BALL_PIXELS_MIN, "%zu fluid pixels", nonzero(&depth));
    if (render(env, "ball.f32", "none.exr", FLAGS("--aov", "smoothed-depth", "--smoothing", "none"), &none)) {
        CHECK_MSG(differing(&none, &depth) == 0, "--smoothing none changed %zu pixels", differing(&none, &depth));
        fc_decoded_image_free(&none);
    }
    if (render(env, "ball.f32", "zero.exr", FLAGS("--aov", "smoothed-depth", "--iterations", "0"), &zero)) {
        CHECK_MSG(differing(&zero, &depth) == 0, "--iterations 0 changed %zu pixels", differing(&zero, &depth));
        fc_decoded_image_free(&zero);
    }
    static const char *const methods[4] = {"curvature", "bilateral", "binomial", "narrow"};
    bool rendered[4];
    for (int m = 0; m < 4; m++) {
        char name[32];
        snprintf(name, sizeof name, "%s.exr", methods[m]);
        rendered[m] = render(env, "ball.f32", name,
                             FLAGS("--aov", "smoothed-depth", "--smoothing", methods[m], "--iterations", "40"),
                             &smoothed[m]);
        if (rendered[m])
            CHECK_MSG(differing(&smoothed[m], &depth) >= BALL_PIXELS_MIN / 2, "%s changed only %zu pixels",
                      methods[m], differing(&smoothed[m], &depth));
    }
    /* Each method is its own filter: no two give the same surface. */
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++)
            if (rendered[a] && rendered[b])
                CHECK_MSG(differing(&smoothed[a], &smoothed[b]) > 0, "%s and %s agree", methods[a], methods[b]);
    for (int m = 0; m < 4; m++)
        if (rendered[m])
            fc_decoded_image_free(&smoothed[m]);
    fc_decoded_image_free(&depth);
}

static void test_filter_and_resolution_flags(const test_env *env)
{
    CHECK(render_difference(env, "ball.f32", "radius.exr",
                            FLAGS("--aov", "smoothed-depth", "--smoothing", "bilateral", "--filter-radius", "1"),
                            FLAGS("--aov", "smoothed-depth", "--smoothing", "bilateral", "--filter-radius", "8")) > 0);
    CHECK(render_difference(env, "ball.f32", "scale.exr", FLAGS("--aov", "smoothed-depth", "--smooth-scale", "1"),
                            FLAGS("--aov", "smoothed-depth", "--smooth-scale", "0.5")) > 0);
    CHECK(render_difference(env, "ball.f32", "tscale.exr", FLAGS("--aov", "thickness", "--thickness-scale", "1"),
                            FLAGS("--aov", "thickness", "--thickness-scale", "0.25")) > 0);
    CHECK(render_difference(env, "ball.f32", "tblur.exr", FLAGS("--aov", "thickness", "--thickness-blur", "0"),
                            FLAGS("--aov", "thickness", "--thickness-blur", "8")) > 0);
}

static void test_noise_and_foam_flags(const test_env *env)
{
    fc_decoded_image off, on;
    if (render(env, "ball.f32", "noise0.exr", FLAGS("--aov", "noise", "--noise", "0"), &off)) {
        CHECK_MSG(nonzero(&off) == 0, "noise 0 left %zu pixels", nonzero(&off));
        fc_decoded_image_free(&off);
    }
    if (render(env, "ball.f32", "noise2.exr", FLAGS("--aov", "noise", "--noise", "2"), &on)) {
        CHECK_MSG(nonzero(&on) >= BALL_PIXELS_MIN / 2, "noise 2 on %zu pixels only", nonzero(&on));
        fc_decoded_image_free(&on);
    }
    /* Foam whitens the noisy surface, and the spray droplets faster than foam-tau. */
    CHECK(render_difference(env, "ball.f32", "foam.exr", FLAGS("--noise", "2", "--foam", "0"),
                            FLAGS("--noise", "2", "--foam", "5")) > 0);
    CHECK(render_difference(env, "ballv.csv", "tau.exr",
                            FLAGS("--density-threshold", "500", "--foam", "5", "--foam-tau", "0.5"),
                            FLAGS("--density-threshold", "500", "--foam", "5", "--foam-tau", "100")) > 0);
}

/* Every particle has density 1000: a threshold above it makes them all spray,
 * which the surface depth does not show; one below it changes nothing. */
static void test_density_threshold(const test_env *env)
{
    fc_decoded_image all, below, above;
    if (!render(env, "ball.csv", "dens.exr", FLAGS("--aov", "depth"), &all))
        return;
    if (render(env, "ball.csv", "dens500.exr", FLAGS("--aov", "depth", "--density-threshold", "500"), &below)) {
        CHECK(differing(&all, &below) == 0);
        fc_decoded_image_free(&below);
    }
    if (render(env, "ball.csv", "dens2000.exr", FLAGS("--aov", "depth", "--density-threshold", "2000"), &above)) {
        CHECK_MSG(nonzero(&above) == 0, "%zu surface pixels above the threshold", nonzero(&above));
        fc_decoded_image_free(&above);
    }
    CHECK(nonzero(&all) >= BALL_PIXELS_MIN);
    fc_decoded_image_free(&all);
}

/* Without --density-threshold no threshold is set, densities or not (a
 * threshold from the densities turned thin crowns into dust): ballv.csv
 * renders as with --density-threshold 0, and its droplets (density 10) leave
 * the surface only when a threshold is given. */
static void test_no_spray_threshold_by_default(const test_env *env)
{
    fc_decoded_image chosen, given, off;
    if (!render(env, "ballv.csv", "spray_default.exr", FLAGS("--aov", "depth"), &chosen))
        return;
    if (render(env, "ballv.csv", "spray_off.exr", FLAGS("--aov", "depth", "--density-threshold", "0"), &off)) {
        CHECK_MSG(differing(&chosen, &off) == 0, "%zu pixels differ from --density-threshold 0",
                  differing(&chosen, &off));
        fc_decoded_image_free(&off);
    }
    if (render(env, "ballv.csv", "spray_500.exr", FLAGS("--aov", "depth", "--density-threshold", "500"), &given)) {
        CHECK_MSG(differing(&chosen, &given) > 0, "--density-threshold 500 left the droplets in the surface");
        fc_decoded_image_free(&given);
    }
    fc_decoded_image_free(&chosen);
}

static void test_shading_flags(const test_env *env)
{
    fc_decoded_image red, blue;
    if (render(env, "ball.f32", "red.png", FLAGS("--color", "1,0,0", "--absorption", "1,1,1"), &red)) {
        const uint8_t *c = pixel(&red, WIDTH / 2, HEIGHT / 2);
        CHECK_MSG(c[0] > c[2] + 60, "--color 1,0,0 gives %d,%d,%d", c[0], c[1], c[2]);
        fc_decoded_image_free(&red);
    }
    if (render(env, "ball.f32", "blue.png", FLAGS("--color", "0,0,1", "--absorption", "1,1,1"), &blue)) {
        const uint8_t *c = pixel(&blue, WIDTH / 2, HEIGHT / 2);
        CHECK_MSG(c[2] > c[0] + 60, "--color 0,0,1 gives %d,%d,%d", c[0], c[1], c[2]);
        fc_decoded_image_free(&blue);
    }
    CHECK(render_difference(env, "ball.f32", "absorb.png", FLAGS("--absorption", "0,0,0"),
                            FLAGS("--absorption", "50,50,50")) > 0);
    CHECK(render_difference(env, "ball.f32", "ior.png", FLAGS("--ior", "1"), FLAGS("--ior", "3")) > 0);
    CHECK(render_difference(env, "ball.f32", "refract.png", FLAGS("--refraction", "0"),
                            FLAGS("--refraction", "400")) > 0);
    CHECK(render_difference(env, "ball.f32", "spec.exr", FLAGS("--specular", "0"), FLAGS("--specular", "10")) > 0);
    CHECK(render_difference(env, "ball.f32", "shine.png", FLAGS("--shininess", "1"),
                            FLAGS("--shininess", "10000")) > 0);
}

static bool near_colour(const uint8_t *p, int r, int g, int b, int tolerance)
{
    return abs(p[0] - r) <= tolerance && abs(p[1] - g) <= tolerance && abs(p[2] - b) <= tolerance;
}

/* A solid background fills every pixel the fluid does not cover, through the
 * server's sRGB decode and re-encode. */
static void test_background(const test_env *env)
{
    char path[PATH_SIZE];
    fc_decoded_image plain, framed;
    if (!render(env, "ball.f32", "plain.png", NO_FLAGS, &plain))
        return;
    if (render(env, "ball.f32", "framed.png", FLAGS("--background", scratch(env, "magenta.png", path)), &framed)) {
        const uint32_t corners[4][2] = {{0, 0}, {WIDTH - 1, 0}, {0, HEIGHT - 1}, {WIDTH - 1, HEIGHT - 1}};
        for (int i = 0; i < 4; i++) {
            const uint8_t *p = pixel(&framed, corners[i][0], corners[i][1]);
            CHECK_MSG(near_colour(p, 200, 40, 120, 2), "corner %d is %d,%d,%d", i, p[0], p[1], p[2]);
            CHECK(!near_colour(pixel(&plain, corners[i][0], corners[i][1]), 200, 40, 120, 20));
        }
        const uint8_t *centre = pixel(&framed, WIDTH / 2, HEIGHT / 2);
        CHECK_MSG(!near_colour(centre, 200, 40, 120, 20), "no fluid in front of the background");
        fc_decoded_image_free(&framed);
    }
    fc_decoded_image_free(&plain);
}

/* A red sky reflects red, a blue one blue; six files in a list are the same as a directory of them. */
static void test_cubemap(const test_env *env)
{
    char red_dir[PATH_SIZE], blue_dir[PATH_SIZE];
    scratch(env, "red", red_dir);
    scratch(env, "blue", blue_dir);
    char list[6 * (PATH_SIZE + 8)] = "";
    static const char *const stems[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (int i = 0; i < 6; i++) {
        size_t used = strlen(list);
        snprintf(list + used, sizeof list - used, "%s%s/%s.png", i ? "," : "", red_dir, stems[i]);
    }
    fc_decoded_image red, blue, listed;
    bool have_red = render(env, "ball.f32", "cube-red.png", FLAGS("--cubemap", red_dir), &red);
    bool have_blue = render(env, "ball.f32", "cube-blue.png", FLAGS("--cubemap", blue_dir), &blue);
    if (have_red && have_blue) {
        const uint8_t *r = pixel(&red, WIDTH / 2, HEIGHT / 2), *b = pixel(&blue, WIDTH / 2, HEIGHT / 2);
        CHECK_MSG(r[0] > b[0] && b[2] > r[2], "red sky %d,%d,%d, blue sky %d,%d,%d", r[0], r[1], r[2], b[0], b[1],
                  b[2]);
    }
    if (have_red && render(env, "ball.f32", "cube-list.png", FLAGS("--cubemap", list), &listed)) {
        CHECK(differing(&red, &listed) == 0);
        fc_decoded_image_free(&listed);
    }
    if (have_red)
        fc_decoded_image_free(&red);
    if (have_blue)
        fc_decoded_image_free(&blue);
}

static void expect_exit(const test_env *env, int expected, const char *input, const char *const *flags,
                        const char *in_message)
{
    cli_result r;
    run_snapshot(env, input, "never.png", flags, &r);
    CHECK_MSG(r.status == expected, "%s %s: exit %d, expected %d; stderr: %s", flags[0], flags[1] ? flags[1] : "",
              r.status, expected, r.err);
    CHECK_MSG(strncmp(r.err, "fluidcast: ", 11) == 0 && strstr(r.err, in_message), "stderr lacks \"%s\": %s",
              in_message, r.err);
    CHECK_MSG(r.out[0] == '\0', "stdout: %s", r.out);
}

/* Each flag's domain is checked before anything is sent: usage errors naming the flag. */
static void test_bad_values_are_usage_errors(const test_env *env)
{
    static const char *const bad[][2] = {
        {"--smooth-scale", "0.75"},   {"--smooth-scale", "0"},         {"--iterations", "1001"},
        {"--filter-radius", "65"},    {"--noise", "-1"},               {"--foam", "11"},
        {"--foam-tau", "0"},          {"--foam-decay", "1"},           {"--density-threshold", "-1"},
        {"--color", "1,2,0"},         {"--absorption", "-1,0,0"},      {"--ior", "0.5"},
        {"--refraction", "1001"},     {"--specular", "11"},            {"--shininess", "0.5"},
        {"--thickness-scale", "2"},   {"--thickness-blur", "33"},      {"--smoothing", "gaussian"},
        {"--aov", "colour"},          {"--cubemap", "a.png,b.png"},    {"--radius", "0"},
        {"--noise", "lots"},          {"--color-by", "pressure"},      {"--range", "2:1"},
        {"--range", "1"},             {"--range", "a:1"},              {"--range", "0:inf"},
        {"--range", ":1"},            {"--colormap", "jet"},           {"--colormap", "turbo"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        expect_exit(env, 2, "ball.f32", FLAGS(bad[i][0], bad[i][1]), bad[i][0]);
    char path[PATH_SIZE];
    expect_exit(env, 3, "ball.f32", FLAGS("--background", scratch(env, "missing.png", path)), "missing.png");
    expect_exit(env, 3, "ball.f32", FLAGS("--cubemap", env->dir), "has no px");
}

/* An OBJ box [lo, hi], faces wound counter-clockwise seen from outside. */
static bool write_box_obj(const char *path, const float lo[3], const float hi[3])
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    for (int c = 0; c < 8; c++)
        fprintf(f, "v %g %g %g\n", (double)(c & 1 ? hi[0] : lo[0]), (double)(c & 2 ? hi[1] : lo[1]),
                (double)(c & 4 ? hi[2] : lo[2]));
    fputs("f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n", f);
    return fclose(f) == 0;
}

/* The same box as VTK XML PolyData (ascii; six quads in Polys). */
static bool write_box_vtp(const char *path, const float lo[3], const float hi[3])
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    fputs("<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n<PolyData>\n"
          "<Piece NumberOfPoints=\"8\" NumberOfPolys=\"6\">\n<Points>\n"
          "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n", f);
    for (int c = 0; c < 8; c++)
        fprintf(f, "%g %g %g\n", (double)(c & 1 ? hi[0] : lo[0]), (double)(c & 2 ? hi[1] : lo[1]),
                (double)(c & 4 ? hi[2] : lo[2]));
    fputs("</DataArray>\n</Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n"
          "0 2 3 1 4 5 7 6 0 1 5 4 2 6 7 3 0 4 6 2 1 3 7 5\n</DataArray>\n"
          "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 8 12 16 20 24</DataArray>\n"
          "</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n", f);
    return fclose(f) == 0;
}

/* --mesh through the real daemon: a box between the camera (y = -4) and the
 * ball leaves no fluid in the depth image, as glass it hides nothing; a closed
 * tank around the ball hides it unless hide-near culls its near wall; a %d
 * pattern takes frame 0 in a snapshot; bad options are usage errors, a missing
 * or broken mesh file an input error (exit 3) naming it. The wall as a .vtp
 * hides the ball as the .obj one does. */
static void test_mesh(const test_env *env)
{
    static const char strips_vtp[] = "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"0\" "
                                     "NumberOfStrips=\"1\"><Points><DataArray type=\"Float32\" "
                                     "NumberOfComponents=\"3\" format=\"ascii\"/></Points></Piece></PolyData>"
                                     "</VTKFile>";
    char path[PATH_SIZE];
    bool ok = write_box_obj(scratch(env, "wall.obj", path), (float[3]){-3, -2, -3}, (float[3]){3, -1.8f, 3}) &&
              write_box_obj(scratch(env, "wall_0000.obj", path), (float[3]){-3, -2, -3}, (float[3]){3, -1.8f, 3}) &&
              write_box_obj(scratch(env, "tank.obj", path), (float[3]){-1, -1, -1}, (float[3]){1, 1, 1}) &&
              write_box_vtp(scratch(env, "wall.vtp", path), (float[3]){-3, -2, -3}, (float[3]){3, -1.8f, 3}) &&
              write_bytes(scratch(env, "broken.obj", path), (const uint8_t *)"v 0 0\n", 6) &&
              write_bytes(scratch(env, "strips.vtp", path), (const uint8_t *)strips_vtp, strlen(strips_vtp));
    CHECK(ok);
    if (!ok)
        return;
    fc_decoded_image plain, wall, glass, pattern, tank, open;
    char wall_arg[PATH_SIZE + 32], glass_arg[PATH_SIZE + 32], pattern_arg[PATH_SIZE], tank_arg[PATH_SIZE],
        open_arg[PATH_SIZE + 16];
    snprintf(wall_arg, sizeof wall_arg, "%s:color=1,0,0", scratch(env, "wall.obj", path));
    snprintf(glass_arg, sizeof glass_arg, "%s:opacity=0.3:color=0.2,0.4,1", scratch(env, "wall.obj", path));
    snprintf(pattern_arg, sizeof pattern_arg, "%s", scratch(env, "wall_%04d.obj", path));
    snprintf(tank_arg, sizeof tank_arg, "%s", scratch(env, "tank.obj", path));
    snprintf(open_arg, sizeof open_arg, "%s:hide-near", scratch(env, "tank.obj", path));
    if (render(env, "ball.f32", "mesh_plain.exr", FLAGS("--aov", "depth"), &plain)) {
        size_t fluid = nonzero(&plain);
        CHECK_MSG(fluid >= BALL_PIXELS_MIN, "%zu fluid pixels", fluid);
        if (render(env, "ball.f32", "mesh_wall.exr", FLAGS("--aov", "depth", "--mesh", wall_arg), &wall)) {
            CHECK_MSG(nonzero(&wall) == 0, "behind the wall %zu fluid pixels", nonzero(&wall));
            fc_decoded_image_free(&wall);
        }
        char vtp_arg[PATH_SIZE];
        fc_decoded_image vtp;
        snprintf(vtp_arg, sizeof vtp_arg, "%s", scratch(env, "wall.vtp", path));
        if (render(env, "ball.f32", "mesh_vtp.exr", FLAGS("--aov", "depth", "--mesh", vtp_arg), &vtp)) {
            CHECK_MSG(nonzero(&vtp) == 0, "behind the .vtp wall %zu fluid pixels", nonzero(&vtp));
            fc_decoded_image_free(&vtp);
        }
        if (render(env, "ball.f32", "mesh_glass.exr", FLAGS("--aov", "depth", "--mesh", glass_arg), &glass)) {
            CHECK_MSG(nonzero(&glass) == fluid, "behind glass %zu fluid pixels of %zu", nonzero(&glass), fluid);
            fc_decoded_image_free(&glass);
        }
        if (render(env, "ball.f32", "mesh_pattern.exr", FLAGS("--aov", "depth", "--mesh", pattern_arg), &pattern)) {
            CHECK_MSG(nonzero(&pattern) == 0, "the pattern's frame 0: %zu fluid pixels", nonzero(&pattern));
            fc_decoded_image_free(&pattern);
        }
        if (render(env, "ball.f32", "mesh_tank.exr", FLAGS("--aov", "depth", "--mesh", tank_arg), &tank)) {
            CHECK_MSG(nonzero(&tank) == 0, "inside the closed tank %zu fluid pixels", nonzero(&tank));
            fc_decoded_image_free(&tank);
        }
        if (render(env, "ball.f32", "mesh_open.exr", FLAGS("--aov", "depth", "--mesh", open_arg), &open)) {
            CHECK_MSG(nonzero(&open) == fluid && differing(&open, &plain) == 0,
                      "hide-near: %zu fluid pixels of %zu, %zu differ", nonzero(&open), fluid, differing(&open, &plain));
            fc_decoded_image_free(&open);
        }
        fc_decoded_image_free(&plain);
    }
    expect_exit(env, 2, "ball.f32", FLAGS("--mesh", "box.txt"), "--mesh");
    expect_exit(env, 2, "ball.f32", FLAGS("--mesh", "box.obj:opacity=2"), "opacity");
    expect_exit(env, 2, "ball.f32", FLAGS("--mesh", "box.obj:color=1,1"), "color");
    expect_exit(env, 2, "ball.f32", FLAGS("--mesh", "box.obj:shiny=1"), "shiny");
    expect_exit(env, 3, "ball.f32", FLAGS("--mesh", scratch(env, "missing.obj", path)), "missing.obj");
    expect_exit(env, 3, "ball.f32", FLAGS("--mesh", scratch(env, "broken.obj", path)), "three numbers");
    expect_exit(env, 3, "ball.f32", FLAGS("--mesh", scratch(env, "strips.vtp", path)), "no Polys");
}

/* --color-by: speed on a frame with velocities changes the image and
 * prints the range it chose (the 2nd to 98th percentile; every particle of
 * ballv.csv moves at 3, and a constant v gets [v, v + 1]); --range fixes it and moves the colours; density colours too;
 * a frame without the attribute is the server's INVALID_VALUE naming it
 * (exit 5), and --range or --colormap without --color-by a usage error. */
static void test_color_by(const test_env *env)
{
    CHECK(render_difference(env, "ballv.csv", "plain.png", NO_FLAGS, FLAGS("--color-by", "speed")) > BALL_PIXELS_MIN);
    cli_result r;
    run_snapshot(env, "ballv.csv", "speed.png", FLAGS("--color-by", "speed", "--colormap", "turbo"), &r);
    CHECK_MSG(r.status == 0 && strstr(r.out, "color range: speed 3:4 ") && strstr(r.out, "--range 3:4"),
              "exit %d, stdout: %s", r.status, r.out);
    run_snapshot(env, "ballv.csv", "speed.png", FLAGS("--color-by", "speed", "--range", "0:5"), &r);
    CHECK_MSG(r.status == 0 && !strstr(r.out, "color range"), "exit %d, stdout: %s", r.status, r.out);
    /* Every surface particle has density 1000: the middle of viridis against its bottom. */
    CHECK(render_difference(env, "ballv.csv", "dens.png", FLAGS("--color-by", "density", "--range", "0:2000"),
                            FLAGS("--color-by", "density", "--range", "1500:2000")) > BALL_PIXELS_MIN);
    expect_exit(env, 5, "ball.csv", FLAGS("--color-by", "speed"), "velocities");
    expect_exit(env, 5, "ball.f32", FLAGS("--color-by", "density"), "densities");
    expect_exit(env, 2, "ballv.csv", FLAGS("--range", "0:1"), "--range");
}

/* Runs a 160x120 snapshot of ballv.csv coloured by speed with `extra` and decodes it. */
static bool legend_render(const test_env *env, const char *output, const char *const *extra, cli_result *r,
                          fc_decoded_image *img)
{
    const char *flags[MAX_ARGS] = {"--color-by", "speed", "--range", "0:5", "--size", "160x120"};
    size_t n = 6;
    for (size_t i = 0; extra[i]; i++)
        flags[n++] = extra[i];
    flags[n] = NULL;
    run_snapshot(env, "ballv.csv", output, flags, r);
    CHECK_MSG(r->status == 0, "%s: exit %d: %s", output, r->status, r->err);
    char path[PATH_SIZE];
    size_t size = 0;
    uint8_t *data = r->status == 0 ? read_whole_file(scratch(env, output, path), &size) : NULL;
    fc_error err;
    fc_code code = data ? fc_decode_image(data, size, "png", false, img, &err) : FC_ERR_IO;
    free(data);
    CHECK_MSG(code == FC_OK, "decoding %s", output);
    return code == FC_OK;
}

/* --legend: its pixels (it reports where its box is) lie only in that box,
 * and they fill much of it; it needs --color-by. */
static void test_legend(const test_env *env)
{
    cli_result plain_run, legend_run;
    fc_decoded_image plain, legend;
    if (!legend_render(env, "nolegend.png", NO_FLAGS, &plain_run, &plain))
        return;
    if (legend_render(env, "legend.png", FLAGS("--legend"), &legend_run, &legend)) {
        int x0 = -1, x1 = -1, y0 = -1, y1 = -1;
        const char *line = strstr(legend_run.out, "legend: ");
        CHECK_MSG(line && sscanf(line, "legend: columns %d..%d, rows %d..%d", &x0, &x1, &y0, &y1) == 4,
                  "stdout: %s", legend_run.out);
        size_t inside = 0, outside = 0;
        for (uint32_t y = 0; y < plain.height; y++)
            for (uint32_t x = 0; x < plain.width; x++) {
                bool differs = memcmp(pixel(&plain, x, y), pixel(&legend, x, y), plain.channels) != 0;
                bool in_box = (int)x >= x0 && (int)x <= x1 && (int)y >= y0 && (int)y <= y1;
                inside += differs && in_box;
                outside += differs && !in_box;
            }
        CHECK_MSG(outside == 0, "%zu legend pixels outside its box", outside);
        CHECK_MSG(x0 >= 0 && inside * 2 > (size_t)(x1 - x0 + 1) * (size_t)(y1 - y0 + 1),
                  "%zu pixels changed in the box %d..%d x %d..%d", inside, x0, x1, y0, y1);
        fc_decoded_image_free(&legend);
    }
    fc_decoded_image_free(&plain);
    expect_exit(env, 2, "ballv.csv", FLAGS("--legend"), "--legend");
    expect_exit(env, 2, "ballv.csv", FLAGS("--color-by", "speed", "--legend", "--aov", "depth"), "--legend");
}

/* Images the server cannot use are its INVALID_VALUE, reported as a server error. */
static void test_server_rejects_images(const test_env *env)
{
    char path[PATH_SIZE], list[6 * PATH_SIZE + 8];
    expect_exit(env, 5, "ball.f32", FLAGS("--background", scratch(env, "broken.png", path)), "server: BACKGROUND");
    snprintf(list, sizeof list, "%s/red/px.png,%s/red/nx.png,%s/red/py.png,%s/red/ny.png,%s/red/pz.png,%s", env->dir,
             env->dir, env->dir, env->dir, env->dir, scratch(env, "rect.png", path));
    expect_exit(env, 5, "ball.f32", FLAGS("--cubemap", list), "not square");
}

static void remove_scratch(const test_env *env)
{
    char command[128];
    snprintf(command, sizeof command, "rm -rf '%s'", env->dir);
    if (system(command) != 0)
        fprintf(stderr, "could not remove %s\n", env->dir);
}

int main(void)
{
    test_env env;
    strcpy(env.dir, "/tmp/fluidcast-params-test-XXXXXX");
    if (!mkdtemp(env.dir) || !write_inputs(&env)) {
        fprintf(stderr, "cannot set up the scratch directory\n");
        return 1;
    }
    strcpy(env.server, "127.0.0.1:1");   /* never reached: usage errors come first */
    test_bad_values_are_usage_errors(&env);

    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        remove_scratch(&env);
        return 1;
    }
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_smoothing_reaches_the_server(&env);
    test_filter_and_resolution_flags(&env);
    test_noise_and_foam_flags(&env);
    test_density_threshold(&env);
    test_no_spray_threshold_by_default(&env);
    test_shading_flags(&env);
    test_background(&env);
    test_cubemap(&env);
    test_server_rejects_images(&env);
    test_color_by(&env);
    test_legend(&env);
    test_mesh(&env);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    remove_scratch(&env);
    return test_result();
}
