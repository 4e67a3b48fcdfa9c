/* test_foam.c — aerated foam (foam_classes.h, foam_pass.h) through the real
 * pipeline: where a slab's particles converge, the colour image turns whiter
 * (brighter and less saturated) than the same surface without foam; a calm
 * slab, at rest or moving as one body, renders bit for bit as with foam off;
 * foam off after foam renders bit for bit as before it, and a calm frame
 * uploaded after a foamy one shows none of its foam; other images than the
 * colour image are untouched. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "shading_fixture.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 72
#define SIDE 16
#define LAYERS 2
#define COUNT (SIDE * SIDE * LAYERS)
#define SPACING 0.1f
#define RADIUS 0.08f
/* The particles within this distance of the slab's axis converge on it. */
#define CONVERGING_RADIUS 0.35f
#define CONVERGING_RATE 5.0f

typedef struct slab {
    float positions[3 * COUNT];
    float velocity[3 * COUNT];
    fc_frame frame;
} slab;

/* A SIDE x SIDE x LAYERS slab facing the axis camera, its front at z = 0;
 * every particle moves by `drift` along x, and those near its axis converge
 * on it at `converge` per unit of distance. */
static void make_slab(slab *s, float converge, float drift)
{
    memset(s, 0, sizeof *s);
    int n = 0;
    float half = 0.5f * (float)(SIDE - 1) * SPACING;
    for (int k = 0; k < LAYERS; k++)
        for (int j = 0; j < SIDE; j++)
            for (int i = 0; i < SIDE; i++, n++) {
                float x = (float)i * SPACING - half, y = (float)j * SPACING - half;
                s->positions[3 * n] = x;
                s->positions[3 * n + 1] = y;
                s->positions[3 * n + 2] = -(float)k * SPACING;
                bool inside = sqrtf(x * x + y * y) < CONVERGING_RADIUS;
                s->velocity[3 * n] = drift - (inside ? converge * x : 0.0f);
                s->velocity[3 * n + 1] = inside ? -converge * y : 0.0f;
            }
    s->frame = (fc_frame){.count = COUNT, .positions = s->positions, .velocity = s->velocity};
}

static fc_settings foam_settings(float aerated_foam)
{
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    settings.spray_neighbours = 2;
    settings.aerated_foam = aerated_foam;
    return settings;
}

static void render(render_fixture *f, const slab *s, float aerated_foam, fc_aov aov, fc_image *out)
{
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);
    fc_settings settings = foam_settings(aerated_foam);
    CHECK_CODE(render_frame(f, &s->frame, &cam, &settings, NULL, aov, aov == FC_AOV_COLOR, out), FC_OK);
}

static bool same_image(const fc_image *a, const fc_image *b)
{
    size_t bytes = (size_t)a->width * a->height * a->channels * (a->type == FC_PIXEL_U8 ? 1 : 4);
    return a->width == b->width && a->height == b->height && a->channels == b->channels && a->type == b->type &&
           memcmp(a->pixels, b->pixels, bytes) == 0;
}

static double luminance(const uint8_t *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/* (max - min) / max of the channels: 0 for grey and white. */
static double saturation(const uint8_t *p)
{
    int hi = p[0] > p[1] ? p[0] : p[1], lo = p[0] < p[1] ? p[0] : p[1];
    hi = hi > p[2] ? hi : p[2];
    lo = lo < p[2] ? lo : p[2];
    return hi > 0 ? (double)(hi - lo) / hi : 0.0;
}

static void test_converging_surface_turns_white(render_fixture *f)
{
    slab s;
    make_slab(&s, CONVERGING_RATE, 0.0f);
    fc_image off = {0}, on = {0};
    render(f, &s, 0.0f, FC_AOV_COLOR, &off);
    render(f, &s, 1.0f, FC_AOV_COLOR, &on);
    double lum_on = 0.0, lum_off = 0.0, sat_on = 0.0, sat_off = 0.0;
    int changed = 0, far_changed = 0;
    const uint8_t *a = on.pixels, *b = off.pixels;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++) {
            size_t k = 4 * ((size_t)row * WIDTH + x);
            if (memcmp(a + k, b + k, 3) == 0)
                continue;
            changed++;
            lum_on += luminance(a + k);
            lum_off += luminance(b + k);
            sat_on += saturation(a + k);
            sat_off += saturation(b + k);
            /* The converging disc spans about 9 pixels around the centre (25 pixels per unit). */
            double dx = (double)x + 0.5 - WIDTH / 2.0, dy = (double)row + 0.5 - HEIGHT / 2.0;
            far_changed += sqrt(dx * dx + dy * dy) > 20.0;
        }
    CHECK_MSG(changed >= 30, "foam changed only %d pixels", changed);
    CHECK_MSG(far_changed == 0, "foam changed %d pixels far from where the slab converges", far_changed);
    CHECK_MSG(lum_on > lum_off + 20.0 * changed, "foam is not brighter: mean luminance %.1f against %.1f",
              lum_on / changed, lum_off / changed);
    CHECK_MSG(sat_on < 0.7 * sat_off, "foam is not whiter: mean saturation %.3f against %.3f", sat_on / changed,
              sat_off / changed);
    fc_image_free(&off);
    fc_image_free(&on);
}

/* At rest, or moving as one body: no velocity differences, no foam. */
static void test_calm_slab_unchanged(render_fixture *f)
{
    const float drifts[2] = {0.0f, 3.0f};
    for (int i = 0; i < 2; i++) {
        slab s;
        make_slab(&s, 0.0f, drifts[i]);
        fc_image off = {0}, on = {0};
        render(f, &s, 0.0f, FC_AOV_COLOR, &off);
        render(f, &s, 1.0f, FC_AOV_COLOR, &on);
        CHECK_MSG(same_image(&off, &on), "a calm slab (drift %g) changed with foam on", (double)drifts[i]);
        fc_image_free(&off);
        fc_image_free(&on);
    }
}

/* Foam leaves nothing behind: off after on is off before it, a calm frame
 * after a foamy one has no foam, and the depth image ignores the setting. */
static void test_foam_leaves_no_state(render_fixture *f)
{
    slab foamy, calm;
    make_slab(&foamy, CONVERGING_RATE, 0.0f);
    make_slab(&calm, 0.0f, 0.0f);
    fc_image before = {0}, on = {0}, after = {0}, calm_off = {0}, calm_after = {0}, depth_off = {0}, depth_on = {0};
    render(f, &foamy, 0.0f, FC_AOV_COLOR, &before);
    render(f, &foamy, 1.0f, FC_AOV_COLOR, &on);
    render(f, &foamy, 0.0f, FC_AOV_COLOR, &after);
    CHECK_MSG(!same_image(&before, &on), "foam on did not change the image");
    CHECK_MSG(same_image(&before, &after), "foam off after foam differs from foam off before it");
    render(f, &calm, 0.0f, FC_AOV_COLOR, &calm_off);
    render(f, &foamy, 1.0f, FC_AOV_COLOR, &on);
    render(f, &calm, 1.0f, FC_AOV_COLOR, &calm_after);
    CHECK_MSG(same_image(&calm_off, &calm_after), "a calm frame after a foamy one shows foam");
    render(f, &foamy, 0.0f, FC_AOV_DEPTH, &depth_off);
    render(f, &foamy, 1.0f, FC_AOV_DEPTH, &depth_on);
    CHECK_MSG(same_image(&depth_off, &depth_on), "foam changed the depth image");
    fc_image *images[] = {&before, &on, &after, &calm_off, &calm_after, &depth_off, &depth_on};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++)
        fc_image_free(images[i]);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_converging_surface_turns_white(&f);
    test_calm_slab_unchanged(&f);
    test_foam_leaves_no_state(&f);
    fixture_close(&f);
    return test_result();
}
