/* test_shading_shape_cues.c — the two shape cues of clear water (issue 26,
 * settings contact_shadow and depth_dimming), each rendered on and off:
 * - contact shadow, on the built-in floor: a block of water floating far above
 *   the floor renders bit for bit the same with it on; the same block resting
 *   on the floor only darkens, and what darkens is its foot (the darkened
 *   pixels lie below the middle of the block's image: measured 82 of 1614
 *   fluid pixels, their mean row 77 against the block's 63);
 * - depth dimming, in a uniformly grey scene (no floor): it only darkens, a
 *   block many particle radii deep darkens where a single sheet beside it
 *   hardly changes (measured 0.879 and 0.972 of their light), and opaque water
 *   (its own colour) is left exactly as it is. */
#include <math.h>
#include <stdlib.h>

#include "fc_settings.h"
#include "shading_fixture.h"
#include "test_util.h"

#define WIDTH 160
#define HEIGHT 120
#define RADIUS 0.025f
#define SPACING 0.04f
#define MAX_PARTICLES 4096
/* A pixel darkened: it lost more than this share of its light. */
#define DARKENED 0.02
/* What "only darkens" forgives: float rounding of the same shading. */
#define ROUNDING 1e-6

typedef struct particles {
    float positions[3 * MAX_PARTICLES];
    uint64_t count;
} particles;

static void add(particles *p, float x, float y, float z)
{
    if (p->count < MAX_PARTICLES) {
        float *q = p->positions + 3 * p->count++;
        q[0] = x, q[1] = y, q[2] = z;
    }
}

/* A block nx x ny x nz particles, its lowest layer at height `bottom` (y up), centred on x = z = 0. */
static void add_block(particles *p, int nx, int ny, int nz, float bottom)
{
    for (int i = 0; i < nx; i++)
        for (int j = 0; j < ny; j++)
            for (int k = 0; k < nz; k++)
                add(p, ((float)i - 0.5f * (float)(nx - 1)) * SPACING, bottom + (float)j * SPACING,
                    ((float)k - 0.5f * (float)(nz - 1)) * SPACING);
}

/* Looking down at the block from the front, a little above it: floor below, sky above. */
static fc_camera front_camera(void)
{
    return (fc_camera){.eye = {0.0f, 0.55f, 1.6f}, .target = {0.0f, 0.12f, 0.0f}, .up = {0.0f, 1.0f, 0.0f},
                       .fov_y_deg = 40.0f, .width = WIDTH, .height = HEIGHT};
}

/* Luminance-free comparison: the largest channel of pixel (x, row). */
static float brightest(const fc_image *img, uint32_t x, uint32_t row)
{
    float v = 0.0f;
    for (uint32_t c = 0; c < 3; c++)
        v = fmaxf(v, channel_f32(img, x, row, c));
    return v;
}

/* The same frame with the cues as `on` has them and as `off` has them. */
static void render_pair(render_fixture *f, const particles *p, const fc_camera *cam, const fc_settings *on,
                        const fc_settings *off, const fc_scene_textures *scene, fc_image *with, fc_image *without)
{
    fc_frame frame = {.count = p->count, .positions = (float *)p->positions};
    CHECK_CODE(render_frame(f, &frame, cam, on, scene, FC_AOV_COLOR, 0, with), FC_OK);
    CHECK_CODE(render_frame(f, &frame, cam, off, scene, FC_AOV_COLOR, 0, without), FC_OK);
}

/* The largest change of any channel of any pixel between the two. */
static double largest_difference(const fc_image *a, const fc_image *b)
{
    double differ = 0.0;
    for (uint32_t row = 0; row < a->height; row++)
        for (uint32_t x = 0; x < a->width; x++)
            for (uint32_t c = 0; c < 3; c++)
                differ = fmax(differ, fabs(channel_f32(a, x, row, c) - channel_f32(b, x, row, c)));
    return differ;
}

/* Pixels where `with` is brighter than `without` in some channel. */
static int brightened(const fc_image *with, const fc_image *without)
{
    int n = 0;
    for (uint32_t row = 0; row < with->height; row++)
        for (uint32_t x = 0; x < with->width; x++)
            for (uint32_t c = 0; c < 3; c++)
                if (channel_f32(with, x, row, c) > channel_f32(without, x, row, c) * (1.0f + ROUNDING) + ROUNDING) {
                    n++;
                    break;
                }
    return n;
}

static void test_contact_shadow(render_fixture *f)
{
    static particles floating, resting;
    add_block(&resting, 12, 6, 8, 0.0f);
    add_block(&floating, 12, 6, 8, 0.0f);
    /* Two particles far below and out of view put the floor 2 units under the floating block. */
    add(&floating, -4.0f, -2.0f, 0.0f);
    add(&floating, 4.0f, -2.0f, 0.0f);
    fc_camera cam = front_camera();
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = RADIUS;
    fc_settings off = settings;
    off.contact_shadow = 0.0f;
    fc_image with = {0}, without = {0};

    render_pair(f, &floating, &cam, &settings, &off, NULL, &with, &without);
    double differ = largest_difference(&with, &without);
    CHECK_MSG(differ == 0.0, "a block 2 units above the floor changed by up to %g with the contact shadow", differ);
    fc_image_free(&with);
    fc_image_free(&without);

    render_pair(f, &resting, &cam, &settings, &off, NULL, &with, &without);
    fc_image depth = {0};
    fc_frame frame = {.count = resting.count, .positions = resting.positions};
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, NULL, FC_AOV_SMOOTHED_DEPTH, 0, &depth), FC_OK);
    int lighter = brightened(&with, &without);
    CHECK_MSG(lighter == 0, "the contact shadow brightened %d pixels", lighter);
    double fluid_rows = 0.0, darkened_rows = 0.0;
    int fluid = 0, darkened = 0;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++) {
            if (pixel_f32(&depth, x, row) <= 0.0f)
                continue;
            fluid++;
            fluid_rows += row;
            if (brightest(&with, x, row) < (1.0 - DARKENED) * brightest(&without, x, row)) {
                darkened++;
                darkened_rows += row;
            }
        }
    CHECK_MSG(fluid > 500, "the resting block covers %d pixels", fluid);
    CHECK_MSG(darkened > fluid / 50, "the contact shadow darkened %d of %d fluid pixels", darkened, fluid);
    if (darkened > 0 && fluid > 0)
        CHECK_MSG(darkened_rows / darkened > fluid_rows / fluid + 2.0,
                  "the darkened pixels' mean row %.1f is not below the block's %.1f (rows grow downwards)",
                  darkened_rows / darkened, fluid_rows / fluid);
    fc_image_free(&with);
    fc_image_free(&without);
    fc_image_free(&depth);
}

/* A uniform grey client background and environment: refraction and reflection show the same grey. */
static fc_scene_textures *grey_scene(render_fixture *f)
{
    static float grey_pixels[WIDTH * HEIGHT * 3];
    static float grey_faces[6][2 * 2 * 3];
    for (int i = 0; i < WIDTH * HEIGHT * 3; i++)
        grey_pixels[i] = 0.5f;
    fc_image background = {.width = WIDTH, .height = HEIGHT, .channels = 3, .type = FC_PIXEL_F32,
                           .pixels = grey_pixels};
    fc_image faces[6];
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < 2 * 2 * 3; j++)
            grey_faces[i][j] = 0.5f;
        faces[i] = (fc_image){.width = 2, .height = 2, .channels = 3, .type = FC_PIXEL_F32,
                              .pixels = grey_faces[i]};
    }
    fc_scene_textures *scene = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_scene_textures_create(f->pipeline, &background, faces, &scene, &err), FC_OK);
    return scene;
}

/* The mean of `with` over `without`, green, over a square of pixels around column x of the middle row. */
static double dimmed_ratio(const fc_image *with, const fc_image *without, uint32_t x)
{
    double a = 0.0, b = 0.0;
    for (uint32_t row = HEIGHT / 2 - 4; row < HEIGHT / 2 + 4; row++)
        for (uint32_t i = x - 4; i < x + 4; i++) {
            a += channel_f32(with, i, row, 1);
            b += channel_f32(without, i, row, 1);
        }
    return a / b;
}

static void test_depth_dimming(render_fixture *f)
{
    /* Facing an axis camera: a single sheet on the left, a block 16 layers deep on the right. */
    static particles p;
    for (int i = 0; i < 10; i++)
        for (int j = 0; j < 14; j++) {
            float x = 0.08f + (float)i * SPACING, y = ((float)j - 6.5f) * SPACING;
            add(&p, -x, y, 0.0f);
            for (int k = 0; k < 16; k++)
                add(&p, x, y, -(float)k * SPACING);
        }
    fc_camera cam = axis_camera(2.2, WIDTH, HEIGHT);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = RADIUS;
    settings.specular = 0.0f;
    settings.depth_dimming = 0.3f;   /* the cue's own effect, at three times the default */
    fc_scene_textures *scene = grey_scene(f);
    if (!scene)
        return;
    fc_settings off = settings;
    off.depth_dimming = 0.0f;
    fc_image with = {0}, without = {0};
    render_pair(f, &p, &cam, &settings, &off, scene, &with, &without);
    int lighter = brightened(&with, &without);
    CHECK_MSG(lighter == 0, "the depth dimming brightened %d pixels", lighter);
    /* The sheet's and the block's middles, where they project (about 32 pixels either side of the centre). */
    double sheet = dimmed_ratio(&with, &without, WIDTH / 2 - 32), block = dimmed_ratio(&with, &without, WIDTH / 2 + 32);
    CHECK_MSG(sheet > 0.95, "a single sheet dimmed to %.3f of its light", sheet);
    CHECK_MSG(block < 0.92, "a block 16 layers deep dimmed only to %.3f of its light", block);
    CHECK_MSG(1.0 - block > 2.0 * (1.0 - sheet), "the deep block dimmed to %.3f, hardly more than the sheet's %.3f",
              block, sheet);
    fc_image_free(&with);
    fc_image_free(&without);

    /* Opaque water shows its own colour: nothing shows through to dim. */
    for (int c = 0; c < 3; c++)
        settings.absorption[c] = off.absorption[c] = 1e6f;
    render_pair(f, &p, &cam, &settings, &off, scene, &with, &without);
    double differ = largest_difference(&with, &without);
    CHECK_MSG(differ < 1e-5, "opaque water changed by up to %g with the depth dimming", differ);
    fc_image_free(&with);
    fc_image_free(&without);
    fc_scene_textures_destroy(scene);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return test_result();
    test_contact_shadow(&f);
    test_depth_dimming(&f);
    fixture_close(&f);
    return test_result();
}
