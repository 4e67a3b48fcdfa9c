/* test_shading_spray.c — spray: the densest-first order that splits surface
 * from spray for any threshold; particles below density_threshold are absent
 * from the depth and thickness images, appear in the colour image as
 * light droplets, whiter the faster they move, and are hidden behind fluid;
 * the order is sorted only when a render asks for a threshold. Classified by
 * neighbours (spray_classes.h), isolated particles are spray and a block and
 * a jet are not, and the droplets differ in size and are shaded within; with
 * velocities each droplet is a streak along its velocity across the view. */
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "anisotropy.h"
#include "density_order.h"
#include "spray_classes.h"
#include "pipeline_internal.h"
#include "shading_fixture.h"
#include "test_util.h"

#define WIDTH 64
#define HEIGHT 48
#define RADIUS 0.15f
#define SURFACE_DENSITY 1000.0f
#define SPRAY_DENSITY 100.0f
#define THRESHOLD 500.0f
/* Slots: a 3x3 sheet of fluid, then the test's spray droplet, then two
 * outriggers far outside the view that fix the bounds (floor, depth range). */
#define SHEET 3
#define DROPLET (SHEET * SHEET)
#define COUNT (DROPLET + 3)

typedef struct spray_frame {
    float positions[3 * COUNT];
    float density[COUNT];
    float velocity[3 * COUNT];
    fc_frame frame;
} spray_frame;

/* The droplet sits at `droplet` (world). */
static void make_frame(spray_frame *s, const float droplet[3], float droplet_speed)
{
    memset(s, 0, sizeof *s);
    make_sheet(s->positions, SHEET, 0.2f);
    memcpy(s->positions + 3 * DROPLET, droplet, 3 * sizeof(float));
    const float outriggers[6] = {-100.0f, -1.0f, -2.0f, 100.0f, 1.0f, 1.0f};
    memcpy(s->positions + 3 * (DROPLET + 1), outriggers, sizeof outriggers);
    for (int i = 0; i < COUNT; i++)
        s->density[i] = i == DROPLET ? SPRAY_DENSITY : SURFACE_DENSITY;
    s->velocity[3 * DROPLET + 1] = droplet_speed;
    s->frame = (fc_frame){.count = COUNT, .positions = s->positions, .density = s->density,
                          .velocity = s->velocity};
}

static fc_settings spray_settings(float threshold)
{
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    settings.density_threshold = threshold;
    settings.foam = 1.0f;
    settings.foam_tau = 0.1f;
    return settings;
}

static void test_density_order(void)
{
    const float density[] = {3.0f, -1.0f, 7.5f, 3.0f, 0.0f, -0.0f, 1e30f, -2.5f, 3.0f};
    const uint32_t expected[] = {6, 2, 0, 3, 8, 4, 5, 1, 7};   /* descending; ties keep frame order */
    fc_density_order order = {0};
    CHECK_CODE(fc_density_order_sort(&order, density, 9, NULL), FC_OK);
    for (int i = 0; i < 9; i++)
        CHECK_MSG(order.order[i] == expected[i], "slot %d: particle %u, expected %u", i, order.order[i],
                  expected[i]);
    /* The spray classes' keys alone (0 and FLT_MAX: the sort skips the
     * digits every key shares), then every key equal (it moves nothing):
     * still the order sorted, ties in frame order. */
    enum { N = 1000 };
    static float keys[N];
    for (int i = 0; i < N; i++)
        keys[i] = i % 7 == 3 ? 0.0f : FLT_MAX;
    CHECK_CODE(fc_density_order_sort(&order, keys, N, NULL), FC_OK);
    int wrong = 0;
    for (int i = 1; i < N; i++) {
        uint32_t a = order.order[i - 1], b = order.order[i];
        wrong += keys[a] < keys[b] || (keys[a] == keys[b] && a > b);
    }
    CHECK_MSG(wrong == 0 && fc_density_order_count_at_least(&order, N, FLT_MIN) == N - (N + 3) / 7,
              "%d slots out of order", wrong);
    for (int i = 0; i < N; i++)
        keys[i] = 2.0f;
    CHECK_CODE(fc_density_order_sort(&order, keys, N, NULL), FC_OK);
    for (int i = 0; i < N; i++)
        wrong += order.order[i] != (uint32_t)i;
    CHECK_MSG(wrong == 0 && fc_density_order_count_at_least(&order, N, 2.0f) == N, "%d slots moved", wrong);
    fc_density_order_free(&order);
}

static void pixel_of(const fc_camera *cam, const float p[3], uint32_t *x, uint32_t *row)
{
    double point[3] = {p[0], p[1], p[2]}, fx, fr;
    analytic_project(cam, point, &fx, &fr);
    *x = (uint32_t)fx;
    *row = (uint32_t)fr;
}

/* Beside the sheet, nearer the camera. */
static const float BESIDE[3] = {0.7f, 0.3f, 0.5f};

static void test_spray_leaves_surface(render_fixture *f)
{
    static spray_frame s;
    make_frame(&s, BESIDE, 0.0f);
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);
    uint32_t x, row;
    pixel_of(&cam, BESIDE, &x, &row);
    fc_image img = {0};
    const fc_aov aovs[] = {FC_AOV_DEPTH, FC_AOV_THICKNESS};
    for (int i = 0; i < 2; i++) {
        fc_settings settings = spray_settings(0.0f);   /* off: the droplet is fluid */
        CHECK_CODE(render_frame(f, &s.frame, &cam, &settings, NULL, aovs[i], 0, &img), FC_OK);
        CHECK(pixel_f32(&img, x, row) > 0.0f);
        CHECK(pixel_f32(&img, WIDTH / 2, HEIGHT / 2) > 0.0f);
        settings = spray_settings(THRESHOLD);
        CHECK_CODE(render_frame(f, &s.frame, &cam, &settings, NULL, aovs[i], 0, &img), FC_OK);
        CHECK_MSG(pixel_f32(&img, x, row) == 0.0f, "aov %d: %g where the spray is", (int)aovs[i],
                  pixel_f32(&img, x, row));
        CHECK(pixel_f32(&img, WIDTH / 2, HEIGHT / 2) > 0.0f);   /* the sheet stays */
    }
    /* A frame without densities has no spray, whatever the threshold. */
    s.frame.density = NULL;
    fc_settings settings = spray_settings(THRESHOLD);
    CHECK_CODE(render_frame(f, &s.frame, &cam, &settings, NULL, FC_AOV_DEPTH, 0, &img), FC_OK);
    CHECK(pixel_f32(&img, x, row) > 0.0f);
    fc_image_free(&img);
}

static double max_difference(const fc_image *a, const fc_image *b)
{
    double most = 0.0;
    size_t floats = fc_image_size(a) / sizeof(float);
    for (size_t i = 0; i < floats; i++)
        most = fmax(most, fabs((double)((const float *)a->pixels)[i] - ((const float *)b->pixels)[i]));
    return most;
}

/* A frame with densities is sorted only for a render with a threshold, once:
 * rendered without one it equals the frame without densities, before the
 * sort exactly (same order), after it up to the rounding of the thickness
 * sums in the other order. */
static void test_sorted_only_for_a_threshold(render_fixture *f)
{
    static spray_frame with_density, without_density;
    make_frame(&with_density, BESIDE, 0.0f);
    make_frame(&without_density, BESIDE, 0.0f);
    without_density.frame.density = NULL;
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);
    uint32_t x, row;
    pixel_of(&cam, BESIDE, &x, &row);
    fc_settings off = spray_settings(0.0f), on = spray_settings(THRESHOLD);
    const uint64_t *sorts = &fc_pipeline_particle_attributes(f->pipeline)->density_sorts;
    uint64_t start = *sorts;
    fc_image reference = {0}, image = {0};
    CHECK_CODE(render_frame(f, &without_density.frame, &cam, &off, NULL, FC_AOV_COLOR, 0, &reference), FC_OK);
    CHECK_CODE(render_frame(f, &with_density.frame, &cam, &off, NULL, FC_AOV_COLOR, 0, &image), FC_OK);
    CHECK(memcmp(image.pixels, reference.pixels, fc_image_size(&reference)) == 0);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &off, FC_AOV_DEPTH, 0, &image, NULL, NULL), FC_OK);
    CHECK_MSG(*sorts == start, "%llu sorts without a threshold", (unsigned long long)(*sorts - start));
    for (int render = 0; render < 2; render++) {
        CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &on, FC_AOV_DEPTH, 0, &image, NULL, NULL), FC_OK);
        CHECK_MSG(pixel_f32(&image, x, row) == 0.0f, "render %d: depth %g where the spray is", render,
                  pixel_f32(&image, x, row));
        CHECK(pixel_f32(&image, WIDTH / 2, HEIGHT / 2) > 0.0f);
        CHECK_MSG(*sorts == start + 1, "render %d: %llu sorts, expected 1", render,
                  (unsigned long long)(*sorts - start));
    }
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &off, FC_AOV_COLOR, 0, &image, NULL, NULL), FC_OK);
    CHECK_MSG(max_difference(&image, &reference) <= 1e-4, "threshold 0 after the sort: differs by %g",
              max_difference(&image, &reference));
    CHECK(*sorts == start + 1);
    fc_image_free(&reference);
    fc_image_free(&image);
}

static float luminance(const fc_image *img, uint32_t x, uint32_t row)
{
    return (channel_f32(img, x, row, 0) + channel_f32(img, x, row, 1) + channel_f32(img, x, row, 2)) / 3.0f;
}

/* Spread between the channels: 0 for grey or white. */
static float tint(const fc_image *img, uint32_t x, uint32_t row)
{
    float lo = channel_f32(img, x, row, 0), hi = lo;
    for (uint32_t c = 1; c < 3; c++) {
        lo = fminf(lo, channel_f32(img, x, row, c));
        hi = fmaxf(hi, channel_f32(img, x, row, c));
    }
    return hi - lo;
}

static void test_spray_drawn_and_whitened(render_fixture *f)
{
    static spray_frame slow, fast, away;
    const float out_of_view[3] = {50.0f, 0.0f, 0.0f};
    make_frame(&slow, BESIDE, 0.0f);
    make_frame(&fast, BESIDE, 10.0f);
    make_frame(&away, out_of_view, 0.0f);
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);
    uint32_t x, row;
    pixel_of(&cam, BESIDE, &x, &row);
    fc_settings settings = spray_settings(THRESHOLD);
    fc_image without = {0}, with_slow = {0}, with_fast = {0};
    CHECK_CODE(render_frame(f, &away.frame, &cam, &settings, NULL, FC_AOV_COLOR, 0, &without), FC_OK);
    CHECK_CODE(render_frame(f, &slow.frame, &cam, &settings, NULL, FC_AOV_COLOR, 0, &with_slow), FC_OK);
    CHECK_CODE(render_frame(f, &fast.frame, &cam, &settings, NULL, FC_AOV_COLOR, 0, &with_fast), FC_OK);
    CHECK_MSG(fabsf(luminance(&with_slow, x, row) - luminance(&without, x, row)) > 0.05f,
              "the droplet does not show: %g vs %g", luminance(&with_slow, x, row), luminance(&without, x, row));
    CHECK_MSG(luminance(&with_slow, x, row) > 0.4f, "a dark droplet: %g", luminance(&with_slow, x, row));
    CHECK_MSG(tint(&with_fast, x, row) < tint(&with_slow, x, row) - 0.02f, "speed does not whiten: tint %g vs %g",
              tint(&with_fast, x, row), tint(&with_slow, x, row));
    /* Spray only adds droplets: away from this one the image is unchanged. */
    int changed_elsewhere = 0;
    for (uint32_t r = 0; r < HEIGHT; r++)
        for (uint32_t c = 0; c < WIDTH; c++) {
            bool near = abs((int)c - (int)x) <= 4 && abs((int)r - (int)row) <= 4;
            changed_elsewhere += !near && luminance(&with_slow, c, r) != luminance(&without, c, r);
        }
    CHECK_MSG(changed_elsewhere == 0, "%d pixels away from the droplet changed", changed_elsewhere);
    fc_image_free(&without);
    fc_image_free(&with_slow);
    fc_image_free(&with_fast);
}

/* Straight behind the sheet's centre, the droplet is hidden by the fluid:
 * the image equals the one with the droplet out of view. */
static void test_spray_hidden_behind_fluid(render_fixture *f)
{
    static spray_frame behind, away;
    const float behind_sheet[3] = {0.0f, 0.0f, -0.6f}, out_of_view[3] = {50.0f, 0.0f, 0.0f};
    make_frame(&behind, behind_sheet, 0.0f);
    make_frame(&away, out_of_view, 0.0f);
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);
    fc_settings settings = spray_settings(THRESHOLD);
    fc_image hidden = {0}, without = {0};
    CHECK_CODE(render_frame(f, &behind.frame, &cam, &settings, NULL, FC_AOV_COLOR, 1, &hidden), FC_OK);
    CHECK_CODE(render_frame(f, &away.frame, &cam, &settings, NULL, FC_AOV_COLOR, 1, &without), FC_OK);
    CHECK(memcmp(hidden.pixels, without.pixels, fc_image_size(&hidden)) == 0);
    fc_image_free(&hidden);
    fc_image_free(&without);
}

/* With the anisotropic kernel the spray pass casts each droplet's shape: a
 * droplet without neighbours is the sphere, pixel for pixel. */
static void test_isolated_droplet_keeps_its_sphere(render_fixture *f)
{
    static spray_frame s;
    make_frame(&s, BESIDE, 0.3f);
    fc_camera cam = axis_camera(4.0, WIDTH, HEIGHT);
    uint32_t x, row;
    pixel_of(&cam, BESIDE, &x, &row);
    fc_settings settings = spray_settings(THRESHOLD);
    fc_image sphere = {0}, shaped = {0};
    CHECK_CODE(render_frame(f, &s.frame, &cam, &settings, NULL, FC_AOV_COLOR, 0, &sphere), FC_OK);
    settings.kernel = FC_KERNEL_ANISOTROPIC;
    CHECK_CODE(render_frame(f, &s.frame, &cam, &settings, NULL, FC_AOV_COLOR, 0, &shaped), FC_OK);
    int differ = 0;
    for (uint32_t r = row - 3; r <= row + 3; r++)
        for (uint32_t c = x - 3; c <= x + 3; c++)
            for (uint32_t k = 0; k < 4; k++)
                differ += channel_f32(&sphere, c, r, k) != channel_f32(&shaped, c, r, k);
    CHECK_MSG(differ == 0, "%d channels of the droplet differ from the sphere's", differ);
    CHECK(luminance(&shaped, x, row) > 0.0f);
    fc_image_free(&sphere);
    fc_image_free(&shaped);
}

/* The neighbour classes (spray_classes.h) on a frame without densities: a
 * 5x5x5 block, a jet of 10 particles in a row (4 neighbours each within 2.2
 * spacings, 2 at its ends) and 5 isolated particles, each far from every
 * other particle; at the default 2 only the isolated ones are spray. */
enum { CLASS_BLOCK = 125, CLASS_ROW = 10, CLASS_ISOLATED = 5, CLASS_COUNT = CLASS_BLOCK + CLASS_ROW + CLASS_ISOLATED };
#define CLASS_SPACING 0.1f

static void make_classes_frame(float *x, bool isolated_in_view)
{
    int n = 0;
    for (int k = 0; k < 5; k++)
        for (int j = 0; j < 5; j++)
            for (int i = 0; i < 5; i++, n++) {
                x[3 * n] = ((float)i - 2.0f) * CLASS_SPACING;
                x[3 * n + 1] = ((float)j - 2.0f) * CLASS_SPACING - 0.35f;
                x[3 * n + 2] = ((float)k - 4.0f) * CLASS_SPACING;
            }
    for (int i = 0; i < CLASS_ROW; i++, n++) {
        x[3 * n] = ((float)i - 4.5f) * CLASS_SPACING;
        x[3 * n + 1] = 0.1f;
        x[3 * n + 2] = 0.0f;
    }
    for (int i = 0; i < CLASS_ISOLATED; i++, n++) {
        x[3 * n] = ((float)i - 2.0f) * 0.3f + (isolated_in_view ? 0.0f : 40.0f);
        x[3 * n + 1] = 0.4f;
        x[3 * n + 2] = 0.0f;
    }
}

static float frame_support(const fc_frame *frame)
{
    return fc_anisotropy_support(fc_frame_estimate_radius(frame));
}

static uint32_t lcg(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

static float uniform(uint32_t *state)
{
    return (float)lcg(state) / (float)(1u << 24);
}

/* Every particle in the class its neighbours, counted pair by pair, give it:
 * a jittered block, a ring of droplets around it, pairs and threes, and
 * droplets flung so far (1e4 supports) that the grid's cells wrap around its
 * table, on negative coordinates too. */
static void test_neighbour_classes_match_pairs(void)
{
    enum { BLOCK = 12, COUNT_MAX = BLOCK * BLOCK * BLOCK + 400 };
    static float x[3 * COUNT_MAX];
    uint32_t state = 12345u, n = 0;
    const float spacing = 0.01f;
    for (int k = 0; k < BLOCK; k++)
        for (int j = 0; j < BLOCK; j++)
            for (int i = 0; i < BLOCK; i++, n++) {
                int at[3] = {i, j, k};
                for (int a = 0; a < 3; a++)
                    x[3 * n + a] = -0.05f + spacing * ((float)at[a] + 0.3f * (uniform(&state) - 0.5f));
            }
    while (n < COUNT_MAX - 8) {
        /* A droplet, some with a partner or two a little over a spacing away. */
        float centre[3] = {0.3f * (uniform(&state) - 0.5f), 0.3f * (uniform(&state) - 0.5f), 0.3f * uniform(&state)};
        uint32_t company = lcg(&state) % 3;
        for (uint32_t m = 0; m <= company && n < COUNT_MAX - 8; m++, n++)
            for (int a = 0; a < 3; a++)
                x[3 * n + a] = centre[a] + 0.015f * (float)m * (a == 0 ? 1.0f : 0.5f);
    }
    const float far[8][3] = {{400, 0, 0}, {400, 0.012f, 0}, {-400, 3, 5}, {0, 0, -300}, {0.02f, 0.01f, -300},
                             {250, -250, 250}, {250, -250, 250.011f}, {-0.2f, 600, 0}};
    for (int m = 0; m < 8; m++, n++)
        memcpy(x + 3 * n, far[m], sizeof far[m]);
    fc_frame frame = {.count = n, .positions = x};
    float support = frame_support(&frame);
    fc_spray_classes classes = {0};
    for (uint32_t enough = 1; enough <= 4; enough++) {
        CHECK_CODE(fc_spray_classes_compute(&classes, &frame, support, enough, NULL), FC_OK);
        CHECK(classes.cells > 0 && classes.cells <= 2 * 4096);
        int wrong = 0, spray = 0;
        for (uint32_t i = 0; i < n; i++) {
            uint32_t found = 0;
            for (uint32_t j = 0; j < n; j++) {
                const float *p = x + 3 * i, *q = x + 3 * j;
                float d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
                found += j != i && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < support * support;
            }
            spray += found < enough;
            wrong += (classes.keys[i] == 0.0f) != (found < enough);
        }
        CHECK_MSG(wrong == 0 && spray > 20, "%d particles in the wrong class of %d spray (%u neighbours)", wrong,
                  spray, enough);
    }
    fc_spray_classes_free(&classes);
}

static void test_neighbour_classes(void)
{
    float x[3 * CLASS_COUNT];
    make_classes_frame(x, true);
    fc_frame frame = {.count = CLASS_COUNT, .positions = x};
    fc_spray_classes classes = {0};
    CHECK_CODE(fc_spray_classes_compute(&classes, &frame, frame_support(&frame), 2, NULL), FC_OK);
    int wrong = 0;
    for (int i = 0; i < CLASS_COUNT; i++)
        wrong += (classes.keys[i] == 0.0f) != (i >= CLASS_BLOCK + CLASS_ROW);
    CHECK_MSG(wrong == 0, "%d particles in the wrong class", wrong);
    /* Two isolated particles alone (one neighbour each at their own
     * spacing) are no body of fluid: neither is spray. */
    fc_frame pair = {.count = 2, .positions = x + 3 * (CLASS_BLOCK + CLASS_ROW)};
    CHECK_CODE(fc_spray_classes_compute(&classes, &pair, frame_support(&pair), 2, NULL), FC_OK);
    CHECK(classes.keys[0] > 0.0f && classes.keys[1] > 0.0f);
    /* Off: nobody is spray. */
    CHECK_CODE(fc_spray_classes_compute(&classes, &frame, frame_support(&frame), 0, NULL), FC_OK);
    for (int i = 0; i < CLASS_COUNT; i++)
        CHECK(classes.keys[i] > 0.0f);
    fc_spray_classes_free(&classes);
}

#define CLASS_WIDTH 200
#define CLASS_HEIGHT 120
#define CLASS_WINDOW 8

/* Through the pipeline: isolated particles leave the surface (depth) while
 * the block and the jet stay, and in colour they are droplets that are not
 * identical white beads: of different sizes, shaded within. */
static void test_isolated_particles_are_droplets(render_fixture *f)
{
    static float in_view[3 * CLASS_COUNT], away[3 * CLASS_COUNT];
    make_classes_frame(in_view, true);
    make_classes_frame(away, false);
    fc_frame frame = {.count = CLASS_COUNT, .positions = in_view}, without = {.count = CLASS_COUNT, .positions = away};
    fc_camera cam = axis_camera(2.0, CLASS_WIDTH, CLASS_HEIGHT);
    fc_settings settings = test_settings(0.6f * CLASS_SPACING, FC_SMOOTHING_NONE, 0);
    settings.spray_neighbours = 2;
    fc_image depth = {0}, color = {0}, reference = {0};
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, NULL, FC_AOV_DEPTH, 0, &depth), FC_OK);
    uint32_t px[CLASS_ISOLATED], row[CLASS_ISOLATED], block_x, block_row, jet_x, jet_row;
    for (int i = 0; i < CLASS_ISOLATED; i++) {
        pixel_of(&cam, in_view + 3 * (CLASS_BLOCK + CLASS_ROW + i), &px[i], &row[i]);
        CHECK_MSG(pixel_f32(&depth, px[i], row[i]) == 0.0f, "isolated particle %d in the surface", i);
    }
    pixel_of(&cam, in_view + 3 * (CLASS_BLOCK / 2), &block_x, &block_row);
    pixel_of(&cam, in_view + 3 * (CLASS_BLOCK + CLASS_ROW / 2), &jet_x, &jet_row);
    CHECK(pixel_f32(&depth, block_x, block_row) > 0.0f);
    CHECK_MSG(pixel_f32(&depth, jet_x, jet_row) > 0.0f, "the jet left the surface");
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, NULL, FC_AOV_COLOR, 0, &color), FC_OK);
    CHECK_CODE(render_frame(f, &without, &cam, &settings, NULL, FC_AOV_COLOR, 0, &reference), FC_OK);
    int smallest = CLASS_WINDOW * CLASS_WINDOW * 4, largest = 0;
    for (int i = 0; i < CLASS_ISOLATED; i++) {
        int covered = 0;
        float darkest = 1e9f, brightest = -1e9f;
        for (uint32_t r = row[i] - CLASS_WINDOW; r <= row[i] + CLASS_WINDOW; r++)
            for (uint32_t c = px[i] - CLASS_WINDOW; c <= px[i] + CLASS_WINDOW; c++) {
                if (luminance(&color, c, r) == luminance(&reference, c, r))
                    continue;
                covered++;
                darkest = fminf(darkest, luminance(&color, c, r));
                brightest = fmaxf(brightest, luminance(&color, c, r));
            }
        printf("droplet %d: %d pixels, luminance %.3f .. %.3f\n", i, covered, darkest, brightest);
        CHECK_MSG(covered > 0, "droplet %d not drawn", i);
        CHECK_MSG(brightest - darkest > 0.1f, "droplet %d is a flat bead: luminance %g .. %g", i, darkest,
                  brightest);
        smallest = covered < smallest ? covered : smallest;
        largest = covered > largest ? covered : largest;
    }
    CHECK_MSG(largest >= smallest + smallest / 2, "droplets all of one size: %d .. %d pixels", smallest, largest);
    fc_image_free(&depth);
    fc_image_free(&color);
    fc_image_free(&reference);
}

/* The extent, in pixels along x and along y, of the pixels of `color` that
 * differ from `reference` within `half` columns and CLASS_STREAK_ROWS rows
 * of (x, row). */
#define CLASS_STREAK_ROWS 12
static void droplet_extent(const fc_image *color, const fc_image *reference, uint32_t x, uint32_t row,
                           uint32_t half, int *along_x, int *along_y)
{
    int lo_x = 1 << 30, hi_x = -1, lo_y = 1 << 30, hi_y = -1;
    for (uint32_t r = row - CLASS_STREAK_ROWS; r <= row + CLASS_STREAK_ROWS; r++)
        for (uint32_t c = x - half; c <= x + half; c++) {
            if (luminance(color, c, r) == luminance(reference, c, r))
                continue;
            lo_x = (int)c < lo_x ? (int)c : lo_x;
            hi_x = (int)c > hi_x ? (int)c : hi_x;
            lo_y = (int)r < lo_y ? (int)r : lo_y;
            hi_y = (int)r > hi_y ? (int)r : hi_y;
        }
    *along_x = hi_x - lo_x + 1;
    *along_y = hi_y - lo_y + 1;
}

/* The isolated droplets of the classes frame, moving along their row (x):
 * each is a streak along x, at least twice as long as it is wide; moving
 * towards the camera, or without velocities, each is round. */
static void test_droplets_streak_along_velocity(render_fixture *f)
{
    static float in_view[3 * CLASS_COUNT], away[3 * CLASS_COUNT], velocity[3 * CLASS_COUNT];
    make_classes_frame(in_view, true);
    make_classes_frame(away, false);
    fc_camera cam = axis_camera(2.0, CLASS_WIDTH, CLASS_HEIGHT);
    fc_settings settings = test_settings(0.6f * CLASS_SPACING, FC_SMOOTHING_NONE, 0);
    settings.spray_neighbours = 2;
    uint32_t px[CLASS_ISOLATED], row[CLASS_ISOLATED];
    for (int i = 0; i < CLASS_ISOLATED; i++)
        pixel_of(&cam, in_view + 3 * (CLASS_BLOCK + CLASS_ROW + i), &px[i], &row[i]);
    uint32_t half = (px[1] - px[0]) / 2;
    /* 0: none, 1: along the row, 2: towards the camera. */
    for (int motion = 0; motion < 3; motion++) {
        memset(velocity, 0, sizeof velocity);
        for (int i = 0; i < CLASS_ISOLATED; i++)
            velocity[3 * (CLASS_BLOCK + CLASS_ROW + i) + (motion == 1 ? 0 : 2)] = 1.0f;
        fc_frame frame = {.count = CLASS_COUNT, .positions = in_view, .velocity = motion ? velocity : NULL};
        fc_frame without = {.count = CLASS_COUNT, .positions = away, .velocity = motion ? velocity : NULL};
        fc_image color = {0}, reference = {0};
        CHECK_CODE(render_frame(f, &frame, &cam, &settings, NULL, FC_AOV_COLOR, 0, &color), FC_OK);
        CHECK_CODE(render_frame(f, &without, &cam, &settings, NULL, FC_AOV_COLOR, 0, &reference), FC_OK);
        for (int i = 0; i < CLASS_ISOLATED; i++) {
            int along_x, along_y;
            droplet_extent(&color, &reference, px[i], row[i], half, &along_x, &along_y);
            printf("motion %d, droplet %d: %d x %d pixels\n", motion, i, along_x, along_y);
            CHECK_MSG(along_y > 0, "motion %d: droplet %d not drawn", motion, i);
            if (motion == 1)
                CHECK_MSG(along_x >= 2 * along_y, "droplet %d moving along x is no streak: %d x %d pixels", i,
                          along_x, along_y);
            else
                CHECK_MSG(along_x <= along_y + 1 && along_y <= along_x + 1,
                          "motion %d: droplet %d is not round: %d x %d pixels", motion, i, along_x, along_y);
        }
        fc_image_free(&color);
        fc_image_free(&reference);
    }
}

int main(void)
{
    test_density_order();
    test_neighbour_classes();
    test_neighbour_classes_match_pairs();
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_spray_leaves_surface(&f);
    test_spray_drawn_and_whitened(&f);
    test_spray_hidden_behind_fluid(&f);
    test_sorted_only_for_a_threshold(&f);
    test_isolated_droplet_keeps_its_sphere(&f);
    test_isolated_particles_are_droplets(&f);
    test_droplets_streak_along_velocity(&f);
    fixture_close(&f);
    return test_result();
}
