/* test_shading_clarity.c — the water's outline and its clarity over a
 * striped client background (issue 26, items 3 and 4):
 * - the outline of a sphere and of a sheet's edge is at most 2 pixels wide:
 *   made opaque and black (huge absorption, black fluid colour, a black
 *   environment, no highlight), the fluid must go from the background's
 *   stripe to black within that, whatever its thickness near the rim;
 * - a layer 10 particle radii deep, with the default look, lets at least
 *   half of the background's stripe contrast through, in every channel. */
#include <math.h>
#include <stdlib.h>

#include "fc_settings.h"
#include "shading_fixture.h"
#include "test_util.h"

#define SIZE 96
#define STRIPE 4        /* pixels per stripe of the background */
#define MAX_OUTLINE 2   /* pixels between background and fluid on a crossing */

/* The fraction of the background a pixel is within (1 - fluid) and the
 * fluid's own value: what counts as a pixel of the outline in between. */
#define BACKGROUND_LEFT 0.98
#define FLUID_LEFT 0.02

static float stripe_pixels[SIZE * SIZE * 3];
static float black_faces[6][2 * 2 * 3];

/* White and black stripes STRIPE pixels wide, along rows (horizontal) or
 * along columns (vertical), of the view's size: it fills the view exactly. */
static fc_scene_textures *striped_scene(render_fixture *f, int horizontal)
{
    for (uint32_t row = 0; row < SIZE; row++)
        for (uint32_t x = 0; x < SIZE; x++) {
            uint32_t along = horizontal ? row : x;
            float v = (along / STRIPE) % 2 == 0 ? 1.0f : 0.0f;
            for (int c = 0; c < 3; c++)
                stripe_pixels[3 * (row * SIZE + x) + c] = v;
        }
    fc_image background = {.width = SIZE, .height = SIZE, .channels = 3, .type = FC_PIXEL_F32,
                           .pixels = stripe_pixels};
    fc_image faces[6];
    for (int i = 0; i < 6; i++)
        faces[i] = (fc_image){.width = 2, .height = 2, .channels = 3, .type = FC_PIXEL_F32,
                              .pixels = black_faces[i]};
    fc_scene_textures *scene = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_scene_textures_create(f->pipeline, &background, faces, &scene, &err), FC_OK);
    return scene;
}

/* The default look, made opaque and black where there is fluid. */
static fc_settings black_fluid(float radius)
{
    fc_settings s;
    fc_settings_default(&s);
    s.radius = radius;
    for (int c = 0; c < 3; c++) {
        s.fluid_color[c] = 0.0f;
        s.absorption[c] = 1e6f;
    }
    s.specular = 0.0f;
    return s;
}

/* Along row `row` (or column, `vertical`), the widest run of pixels that are
 * neither background (within 2% of the first pixel, which shows the white
 * stripe) nor fluid (within 2% of black), between the run of background and
 * the run of fluid on each side; -1 when the line has no fluid. */
static int widest_outline(const fc_image *img, uint32_t line, int vertical)
{
    float white = channel_f32(img, vertical ? line : 0, vertical ? 0 : line, 1);
    int widest = -1, run = 0, seen_fluid = 0;
    for (uint32_t i = 0; i < SIZE; i++) {
        uint32_t x = vertical ? line : i, row = vertical ? i : line;
        double covered = 1.0 - channel_f32(img, x, row, 1) / white;
        if (covered < 1.0 - BACKGROUND_LEFT || covered > 1.0 - FLUID_LEFT) {
            if (covered > 1.0 - FLUID_LEFT)
                seen_fluid = 1;
            if (run > widest)
                widest = run;
            run = 0;
        } else {
            run++;
        }
    }
    return seen_fluid ? (run > widest ? run : widest) : -1;
}

/* Every line through the middle third of the view that shows a white stripe:
 * there the outline crosses it at a steep angle, one pixel's step at most. */
static void check_outline(render_fixture *f, const fc_frame *frame, float radius, const char *what)
{
    for (int vertical = 0; vertical < 2; vertical++) {
        fc_scene_textures *scene = striped_scene(f, !vertical);
        if (!scene)
            return;
        fc_camera cam = axis_camera(5.0, SIZE, SIZE);
        fc_settings settings = black_fluid(radius);
        fc_image img = {0};
        CHECK_CODE(render_frame(f, frame, &cam, &settings, scene, FC_AOV_COLOR, 0, &img), FC_OK);
        int lines = 0;
        for (uint32_t line = SIZE / 3; line < 2 * SIZE / 3; line++) {
            if ((line / STRIPE) % 2 != 0)
                continue;
            int width = widest_outline(&img, line, vertical);
            CHECK_MSG(width >= 0 && width <= MAX_OUTLINE, "%s, %s %u: outline %d pixels wide", what,
                      vertical ? "column" : "row", line, width);
            lines++;
        }
        CHECK(lines >= SIZE / 3 / 2 - 1);
        fc_image_free(&img);
        fc_scene_textures_destroy(scene);
    }
}

static void test_sphere_outline(render_fixture *f)
{
    const float centre[3] = {0.0f, 0.0f, 0.0f};
    fc_frame frame = {.count = 1, .positions = (float *)centre};
    check_outline(f, &frame, 1.0f, "sphere");
}

/* A single sheet of particles a radius apart: its edges are the rims
 * of single sprites, thinner than a particle, where the thickness used to
 * fade the fluid into a halo. */
static void test_sheet_outline(render_fixture *f)
{
    enum { SIDE = 20 };
    static float positions[SIDE * SIDE * 3];
    make_sheet(positions, SIDE, 0.1f);
    fc_frame frame = {.count = SIDE * SIDE, .positions = positions};
    check_outline(f, &frame, 0.1f, "sheet");
}

/* The stripes' contrast in channel c over rows [row0, row1) between columns
 * x0 and x1: the mean of the background's light columns minus that of its
 * dark ones (as striped_scene lays them), so that a ripple in the fluid's
 * colour counts as no contrast let through. */
static double stripe_contrast(const fc_image *img, uint32_t row0, uint32_t row1, uint32_t x0, uint32_t x1,
                              uint32_t c)
{
    double sum[2] = {0.0, 0.0};
    int count[2] = {0, 0};
    for (uint32_t row = row0; row < row1; row++)
        for (uint32_t x = x0; x < x1; x++) {
            int light = (x / STRIPE) % 2 == 0;
            sum[light] += channel_f32(img, x, row, c);
            count[light]++;
        }
    return sum[1] / count[1] - sum[0] / count[0];
}

/* LAYERS sheets one behind the other, spaced so that the spheres span 10
 * radii front to back, about 0.9 of the spacing in radius (the radius
 * fluidcast estimates for such a lattice): the fluid's thickness is several
 * times the depth there, the most absorbing case of a layer that deep. */
static void test_deep_layer_transmits(render_fixture *f)
{
    enum { SIDE = 28, LAYERS = 8 };
    const float radius = 0.1f, spacing = 8.0f * radius / (float)(LAYERS - 1);
    static float positions[SIDE * SIDE * LAYERS * 3];
    for (int k = 0; k < LAYERS; k++) {
        float *layer = positions + 3 * SIDE * SIDE * k;
        make_sheet(layer, SIDE, spacing);
        for (int i = 0; i < SIDE * SIDE; i++)
            layer[3 * i + 2] = -spacing * (float)k;
    }
    fc_frame frame = {.count = SIDE * SIDE * LAYERS, .positions = positions};
    fc_scene_textures *scene = striped_scene(f, 0);
    if (!scene)
        return;
    fc_camera cam = axis_camera(5.0, SIZE, SIZE);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = radius;
    fc_image img = {0};
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, scene, FC_AOV_COLOR, 0, &img), FC_OK);
    /* The layer covers the view's middle (its sides are 3.1 units at a
     * distance of 5, a view of 3.6): compare its middle half, all its rows
     * (whatever the particles' rows fall on), with the view's top rows. */
    const uint32_t lo = SIZE / 4, hi = 3 * SIZE / 4;
    for (uint32_t c = 0; c < 3; c++) {
        double open = stripe_contrast(&img, 0, 2, lo, hi, c);
        double through = stripe_contrast(&img, lo, hi, lo, hi, c);
        CHECK_MSG(open > 0.1, "channel %u: background contrast %g", c, open);
        CHECK_MSG(through >= 0.5 * open, "channel %u: the layer lets %g of the contrast through", c,
                  through / open);
    }
    fc_image_free(&img);
    fc_scene_textures_destroy(scene);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_sphere_outline(&f);
    test_sheet_outline(&f);
    test_deep_layer_transmits(&f);
    fixture_close(&f);
    return test_result();
}
