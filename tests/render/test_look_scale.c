/* test_look_scale.c — the look is unit-free (issue 11): a pool with a ball
 * above it rendered at one size, and the same scene with every position, the
 * radius and the camera multiplied by 1000 (metres to millimetres) and by
 * 0.001, gives the same image, in 8-bit colour (tone-mapped) and in float
 * colour (linear HDR), with the default settings (the sun's shadow on the
 * floor, absorption per radius, refraction per pixel of thickness) and with
 * the anisotropic kernel. A term in absolute world units (absorption not
 * divided by the radius, an epsilon in world units) shows as a difference far
 * beyond the bounds here. */
#include <math.h>
#include <stdint.h>

#include "fc_frame.h"
#include "render_fixture.h"
#include "test_util.h"

#define WIDTH 160
#define HEIGHT 120

/* The scene in its base unit: particles SPACING apart, of radius RADIUS. */
#define SPACING 0.04f
#define RADIUS 0.025f
#define POOL_SIDE 24     /* particles along each side of the pool */
#define POOL_LAYERS 3
#define BALL_RADIUS 0.2f
#define BALL_HEIGHT 0.45f   /* of its centre above the pool's lowest layer */
#define MAX_PARTICLES 4096

/* The bounds, in 1/255 of colour: float noise and rounding leave a mean of
 * 0.0003-0.0004/255 and no pixel more than 1/255 (8-bit) or 0.1/255 (float)
 * apart on llvmpipe. A unit-dependent term leaves far more: absorption not
 * divided by the radius, a mean of 30/255 (8-bit) and 39% of the pixels off
 * at x1000, 10% (8-bit) and 29% (float) off at x0.001; the shadow's
 * extinction not divided by it, 9.5/255 and 35% at x1000, 15% off at x0.001;
 * refraction per world unit of thickness, 28% off both ways. A pixel is off
 * when a channel differs by more than OFF_THRESHOLD; a few may flip at the
 * silhouette on a GPU. */
#define MAX_MEAN_DIFF (0.25 / 255.0)
#define OFF_THRESHOLD (2.5 / 255.0)   /* 8-bit: 3 levels or more */
#define MAX_OFF_FRACTION 0.002

/* Deterministic jitter in [-0.5, 0.5). */
static float jitter(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (float)(*state >> 8) / (float)(1u << 24) - 0.5f;
}

/* A square pool of POOL_LAYERS layers on y = 0 and a ball above its middle,
 * both on a jittered lattice. Returns the particle count. */
static uint64_t make_scene(float *positions)
{
    uint32_t seed = 12345u;
    uint64_t n = 0;
    float half = 0.5f * (float)(POOL_SIDE - 1) * SPACING;
    for (int layer = 0; layer < POOL_LAYERS; layer++)
        for (int i = 0; i < POOL_SIDE; i++)
            for (int k = 0; k < POOL_SIDE; k++) {
                float *p = positions + 3 * n++;
                p[0] = (float)i * SPACING - half + 0.2f * SPACING * jitter(&seed);
                p[1] = (float)layer * SPACING + 0.2f * SPACING * jitter(&seed);
                p[2] = (float)k * SPACING - half + 0.2f * SPACING * jitter(&seed);
            }
    int steps = (int)(BALL_RADIUS / SPACING);
    for (int i = -steps; i <= steps; i++)
        for (int j = -steps; j <= steps; j++)
            for (int k = -steps; k <= steps; k++) {
                float x = (float)i * SPACING, y = (float)j * SPACING, z = (float)k * SPACING;
                if (x * x + y * y + z * z > BALL_RADIUS * BALL_RADIUS || n >= MAX_PARTICLES)
                    continue;
                float *p = positions + 3 * n++;
                p[0] = x + 0.2f * SPACING * jitter(&seed);
                p[1] = BALL_HEIGHT + y + 0.2f * SPACING * jitter(&seed);
                p[2] = z + 0.2f * SPACING * jitter(&seed);
            }
    return n;
}

/* Looking down on the pool from the front, a little from the left. */
static fc_camera base_camera(void)
{
    return (fc_camera){.eye = {-0.35f, 0.95f, 1.45f}, .target = {0.0f, 0.2f, 0.0f}, .up = {0.0f, 1.0f, 0.0f},
                       .fov_y_deg = 40.0f, .width = WIDTH, .height = HEIGHT};
}

/* The scene, its radius and its camera (eye and target) scaled by `s`. */
static void scale_scene(const float *positions, uint64_t count, float s, float *out, fc_camera *cam,
                        fc_settings *settings)
{
    for (uint64_t i = 0; i < 3 * count; i++)
        out[i] = positions[i] * s;
    for (int i = 0; i < 3; i++) {
        cam->eye[i] *= s;
        cam->target[i] *= s;
    }
    settings->radius *= s;
}

typedef struct image_diff {
    double mean;          /* mean absolute difference over the RGB channels */
    double max;
    double off_fraction;  /* of pixels with a channel more than OFF_THRESHOLD apart */
} image_diff;

static double value_at(const fc_image *img, uint32_t x, uint32_t row, uint32_t c)
{
    size_t i = ((size_t)row * img->width + x) * img->channels + c;
    return img->type == FC_PIXEL_U8 ? ((const uint8_t *)img->pixels)[i] / 255.0 : ((const float *)img->pixels)[i];
}

static image_diff compare(const fc_image *a, const fc_image *b)
{
    image_diff d = {0};
    size_t off = 0;
    for (uint32_t row = 0; row < a->height; row++)
        for (uint32_t x = 0; x < a->width; x++) {
            double worst = 0.0;
            for (uint32_t c = 0; c < 3; c++) {
                double va = value_at(a, x, row, c), vb = value_at(b, x, row, c);
                /* Float colour is linear HDR (the sun's glow is far above 1):
                 * relative above 1, absolute below. */
                double diff = fabs(va - vb) / fmax(1.0, fmax(fabs(va), fabs(vb)));
                d.mean += diff;
                worst = fmax(worst, diff);
            }
            d.max = fmax(d.max, worst);
            off += worst > OFF_THRESHOLD;
        }
    double pixels = (double)a->width * a->height;
    d.mean /= 3.0 * pixels;
    d.off_fraction = (double)off / pixels;
    return d;
}

/* Fraction of the image's pixels covered by fluid (the depth AOV). */
static double fluid_fraction(render_fixture *f, const float *positions, uint64_t count, const fc_camera *cam,
                             const fc_settings *settings)
{
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, positions, count, cam, settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    size_t covered = 0;
    for (uint32_t row = 0; row < depth.height; row++)
        for (uint32_t x = 0; x < depth.width; x++)
            covered += pixel_f32(&depth, x, row) > 0.0f;
    double fraction = depth.pixels ? (double)covered / ((double)depth.width * depth.height) : 0.0;
    fc_image_free(&depth);
    return fraction;
}

/* The scene at scale 1 and at `scale`, colour of the given type: the same image. */
static void check_scale(render_fixture *f, const float *positions, uint64_t count, const fc_settings *base,
                        float scale, int want_u8, const char *what)
{
    static float scaled[3 * MAX_PARTICLES];
    fc_camera cam = base_camera(), cam_scaled = base_camera();
    fc_settings settings = *base, settings_scaled = *base;
    scale_scene(positions, count, scale, scaled, &cam_scaled, &settings_scaled);
    fc_image a = {0}, b = {0};
    CHECK_CODE(render_positions(f, positions, count, &cam, &settings, FC_AOV_COLOR, want_u8, &a), FC_OK);
    CHECK_CODE(render_positions(f, scaled, count, &cam_scaled, &settings_scaled, FC_AOV_COLOR, want_u8, &b), FC_OK);
    if (!a.pixels || !b.pixels) {
        CHECK_MSG(0, "%s: no image", what);
        fc_image_free(&a);
        fc_image_free(&b);
        return;
    }
    image_diff d = compare(&a, &b);
    printf("%-20s x%-6g %s: mean %.5f/255, max %.2f/255, %.3f%% of pixels > %.1f/255\n", what, (double)scale,
           want_u8 ? "u8 " : "f32", d.mean * 255.0, d.max * 255.0, 100.0 * d.off_fraction, OFF_THRESHOLD * 255.0);
    CHECK_MSG(d.mean < MAX_MEAN_DIFF, "%s x%g %s: mean difference %g/255", what, (double)scale,
              want_u8 ? "8-bit" : "float", d.mean * 255.0);
    CHECK_MSG(d.off_fraction < MAX_OFF_FRACTION, "%s x%g %s: %g%% of pixels differ by more than %g/255", what,
              (double)scale, want_u8 ? "8-bit" : "float", 100.0 * d.off_fraction, OFF_THRESHOLD * 255.0);
    fc_image_free(&a);
    fc_image_free(&b);
}

static void check_settings(render_fixture *f, const float *positions, uint64_t count, const fc_settings *settings,
                           const char *what)
{
    const float scales[] = {1000.0f, 0.001f};
    for (int s = 0; s < 2; s++)
        for (int want_u8 = 1; want_u8 >= 0; want_u8--)
            check_scale(f, positions, count, settings, scales[s], want_u8, what);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    static float positions[3 * MAX_PARTICLES];
    uint64_t count = make_scene(positions);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = RADIUS;

    fc_camera cam = base_camera();
    double covered = fluid_fraction(&f, positions, count, &cam, &settings);
    printf("%llu particles, fluid on %.1f%% of the image\n", (unsigned long long)count, 100.0 * covered);
    CHECK_MSG(covered > 0.25 && covered < 0.9, "fluid covers %g of the image", covered);

    check_settings(&f, positions, count, &settings, "default (shadow on)");
    fc_settings anisotropic = settings;
    anisotropic.kernel = FC_KERNEL_ANISOTROPIC;
    check_settings(&f, positions, count, &anisotropic, "anisotropic kernel");

    /* The ellipsoids take effect here: the kernels' images differ. */
    fc_image spheres = {0}, ellipsoids = {0};
    CHECK_CODE(render_positions(&f, positions, count, &cam, &settings, FC_AOV_COLOR, 1, &spheres), FC_OK);
    CHECK_CODE(render_positions(&f, positions, count, &cam, &anisotropic, FC_AOV_COLOR, 1, &ellipsoids), FC_OK);
    if (spheres.pixels && ellipsoids.pixels) {
        image_diff d = compare(&spheres, &ellipsoids);
        printf("spheres against ellipsoids: mean %.3f/255, %.1f%% of pixels > %.1f/255\n", d.mean * 255.0,
               100.0 * d.off_fraction, OFF_THRESHOLD * 255.0);
        CHECK_MSG(d.off_fraction > 0.05, "the anisotropic kernel changed only %g%% of the pixels",
                  100.0 * d.off_fraction);
    }
    fc_image_free(&spheres);
    fc_image_free(&ellipsoids);
    fixture_close(&f);
    return test_result();
}
