/* test_shading_noise.c — surface noise and the foam state: the noise image is
 * exactly 0 without noise and linear in the amplitude with it; its pattern
 * belongs to the particles (moving frame and camera together, or reordering
 * the particles with their ids, leaves it unchanged; other ids change it);
 * a particle whose velocity jumps by more than foam_tau gets a raised
 * amplitude that decays by foam_decay per frame, and its noise scales with it;
 * records and amplitudes follow the particles into each frame's draw order. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "foam_state.h"
#include "pipeline_internal.h"
#include "shading_fixture.h"
#include "test_util.h"

#define SIZE 48
#define SHEET 6
#define COUNT (SHEET * SHEET)
#define RADIUS 0.2f
#define SPACING 0.16f

typedef struct sheet_frame {
    float positions[3 * COUNT];
    float velocity[3 * COUNT];
    uint32_t ids[COUNT];
    fc_frame frame;
} sheet_frame;

static void make_frame(sheet_frame *s)
{
    make_sheet(s->positions, SHEET, SPACING);
    memset(s->velocity, 0, sizeof s->velocity);
    for (uint32_t i = 0; i < COUNT; i++)
        s->ids[i] = 1000 + 7 * i;
    s->frame = (fc_frame){.count = COUNT, .positions = s->positions, .velocity = s->velocity, .ids = s->ids};
}

static fc_settings noise_settings(float noise)
{
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_CURVATURE, 10);
    settings.noise = noise;
    return settings;
}

static fc_code render_noise(render_fixture *f, const fc_frame *frame, const fc_camera *cam, float noise,
                            fc_image *out)
{
    fc_settings settings = noise_settings(noise);
    return render_frame(f, frame, cam, &settings, NULL, FC_AOV_NOISE, 0, out);
}

static double max_abs(const fc_image *img)
{
    double peak = 0.0;
    for (size_t i = 0; i < (size_t)img->width * img->height; i++)
        peak = fmax(peak, fabs(((const float *)img->pixels)[i]));
    return peak;
}

/* Largest difference between two one-channel images of the same size. */
static double max_difference(const fc_image *a, const fc_image *b)
{
    double worst = 0.0;
    for (size_t i = 0; i < (size_t)a->width * a->height; i++)
        worst = fmax(worst, fabs(((const float *)a->pixels)[i] - ((const float *)b->pixels)[i]));
    return worst;
}

static void test_off_and_linear(render_fixture *f)
{
    static sheet_frame s;
    make_frame(&s);
    fc_camera cam = axis_camera(3.0, SIZE, SIZE);
    fc_image off = {0}, half = {0}, full = {0};
    CHECK_CODE(render_noise(f, &s.frame, &cam, 0.0f, &off), FC_OK);
    CHECK(off.channels == 1 && off.type == FC_PIXEL_F32 && off.width == SIZE);
    CHECK(max_abs(&off) == 0.0);
    CHECK_CODE(render_noise(f, &s.frame, &cam, 0.5f, &half), FC_OK);
    CHECK_CODE(render_noise(f, &s.frame, &cam, 1.0f, &full), FC_OK);
    CHECK_MSG(max_abs(&half) > 0.05, "peak noise %g", max_abs(&half));
    int positive = 0, negative = 0, doubled = 0;
    for (size_t i = 0; i < (size_t)SIZE * SIZE; i++) {
        float h = ((const float *)half.pixels)[i], w = ((const float *)full.pixels)[i];
        positive += h > 0.0f;
        negative += h < 0.0f;
        doubled += fabsf(w - 2.0f * h) <= 1e-5f;
    }
    CHECK_MSG(positive > 50 && negative > 50, "%d positive, %d negative noise pixels", positive, negative);
    CHECK(doubled == SIZE * SIZE);
    /* Outside the sheet there is no surface to carry noise. */
    CHECK(pixel_f32(&half, 0, 0) == 0.0f);
    fc_image_free(&off);
    fc_image_free(&half);
    fc_image_free(&full);
}

static void test_pattern_moves_with_particles(render_fixture *f)
{
    static sheet_frame s, moved;
    make_frame(&s);
    make_frame(&moved);
    const float shift[3] = {0.25f, -0.125f, 0.5f};   /* exact in binary: no rounding in the shift */
    for (uint32_t i = 0; i < COUNT; i++)
        for (int c = 0; c < 3; c++)
            moved.positions[3 * i + c] += shift[c];
    fc_camera cam = axis_camera(3.0, SIZE, SIZE), moved_cam = cam;
    for (int c = 0; c < 3; c++) {
        moved_cam.eye[c] += shift[c];
        moved_cam.target[c] += shift[c];
    }
    fc_image before = {0}, after = {0}, frame_only = {0};
    CHECK_CODE(render_noise(f, &s.frame, &cam, 1.0f, &before), FC_OK);
    CHECK_CODE(render_noise(f, &moved.frame, &moved_cam, 1.0f, &after), FC_OK);
    double peak = max_abs(&before);
    CHECK_MSG(max_difference(&before, &after) <= 1e-3 * peak, "moved together: differs by %g of %g",
              max_difference(&before, &after), peak);
    /* Moving the particles alone does move the pattern on screen. */
    CHECK_CODE(render_noise(f, &moved.frame, &cam, 1.0f, &frame_only), FC_OK);
    CHECK(max_difference(&before, &frame_only) > 0.1 * peak);
    fc_image_free(&before);
    fc_image_free(&after);
    fc_image_free(&frame_only);
}

static void test_pattern_follows_ids(render_fixture *f)
{
    static sheet_frame s, reversed;
    make_frame(&s);
    make_frame(&reversed);
    for (uint32_t i = 0; i < COUNT; i++) {
        memcpy(reversed.positions + 3 * i, s.positions + 3 * (COUNT - 1 - i), 3 * sizeof(float));
        reversed.ids[i] = s.ids[COUNT - 1 - i];
    }
    fc_camera cam = axis_camera(3.0, SIZE, SIZE);
    fc_image original = {0}, same_ids = {0}, other_ids = {0};
    CHECK_CODE(render_noise(f, &s.frame, &cam, 1.0f, &original), FC_OK);
    CHECK_CODE(render_noise(f, &reversed.frame, &cam, 1.0f, &same_ids), FC_OK);
    double peak = max_abs(&original);
    /* Blending adds the splats in another order: only rounding differs. */
    CHECK_MSG(max_difference(&original, &same_ids) <= 1e-4 * peak, "reordered: differs by %g of %g",
              max_difference(&original, &same_ids), peak);
    for (uint32_t i = 0; i < COUNT; i++)
        reversed.ids[i] = s.ids[i];   /* positions reversed, ids not: each particle has another id */
    CHECK_CODE(render_noise(f, &reversed.frame, &cam, 1.0f, &other_ids), FC_OK);
    CHECK(max_difference(&original, &other_ids) > 0.1 * peak);
    fc_image_free(&original);
    fc_image_free(&same_ids);
    fc_image_free(&other_ids);
}

static fc_settings foam_settings(void)
{
    fc_settings settings = noise_settings(1.0f);
    settings.foam_tau = 0.5f;
    settings.foam_decay = 0.8f;
    return settings;
}

static fc_code advance(render_fixture *f, fc_foam_state *foam, const fc_frame *frame, const fc_settings *settings)
{
    fc_error err = {0};
    fc_code code = fc_pipeline_upload(f->pipeline, frame, NULL, &err);
    if (code == FC_OK)
        code = fc_foam_state_advance(foam, f->pipeline, frame, settings, &err);
    return code;
}

/* Ids 10, 20, 30; the one with id 20 jumps by twice tau in frame 2, the one
 * with id 30 by half tau. Frame 2 lists them in another order. */
static void test_foam_raise_and_decay(render_fixture *f)
{
    fc_foam_state *foam = NULL;
    CHECK_CODE(fc_foam_state_create(&foam, NULL), FC_OK);
    if (!foam)
        return;
    fc_settings settings = foam_settings();
    float positions[9] = {-1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f};
    float velocity[9] = {0};
    uint32_t ids[3] = {10, 20, 30};
    fc_frame frame = {.count = 3, .positions = positions, .velocity = velocity, .ids = ids};
    CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
    CHECK(fc_foam_state_amplitude(foam, 10) == 1.0f && fc_foam_state_amplitude(foam, 20) == 1.0f);

    uint32_t reordered_ids[3] = {30, 10, 20};
    float jumped[9] = {0.0f, 0.25f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f};
    frame.ids = reordered_ids;
    frame.velocity = jumped;
    CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
    float raised = fc_foam_state_amplitude(foam, 20);
    CHECK_MSG(raised > 1.5f, "amplitude after the jump: %g", raised);
    CHECK(fc_foam_state_amplitude(foam, 10) == 1.0f);
    CHECK(fc_foam_state_amplitude(foam, 30) == 1.0f);   /* changed by less than tau */
    CHECK(fc_foam_state_amplitude(foam, 99) == 1.0f);   /* never seen */

    /* Constant velocities from now on: the raise decays geometrically. */
    float previous = raised - 1.0f;
    for (int step = 0; step < 5; step++) {
        CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
        float raise = fc_foam_state_amplitude(foam, 20) - 1.0f;
        CHECK_NEAR(raise, settings.foam_decay * previous, 1e-6);
        previous = raise;
    }
    /* A frame without the particle forgets it; a frame without ids forgets all. */
    frame.count = 2;
    CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
    CHECK(fc_foam_state_amplitude(foam, 20) == 1.0f);
    frame.count = 3;
    frame.velocity[3 * 2] = 5.0f;   /* id 20 again, now moving: a jump, but it has no history */
    CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
    CHECK(fc_foam_state_amplitude(foam, 20) == 1.0f);
    fc_foam_state_destroy(foam);
}

/* The noise is linear in each particle's amplitude: a particle raised by
 * the foam state makes exactly that much more noise at every pixel it
 * covers, and its calm neighbour none. The densities put the second particle
 * first in draw order, so the amplitudes must follow the particles there. */
static void test_foam_scales_noise(render_fixture *f)
{
    fc_foam_state *foam = NULL;
    CHECK_CODE(fc_foam_state_create(&foam, NULL), FC_OK);
    if (!foam)
        return;
    fc_settings settings = foam_settings();
    float positions[6] = {-0.6f, 0.0f, 0.0f, 0.6f, 0.0f, 0.0f}, velocity[6] = {0};
    float density[2] = {1.0f, 2.0f};
    uint32_t ids[2] = {5, 6};
    fc_frame frame = {.count = 2, .positions = positions, .density = density, .velocity = velocity, .ids = ids};
    fc_camera cam = axis_camera(3.0, 48, 32);
    fc_image calm = {0}, violent = {0};
    CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_NOISE, 0, &calm, NULL, NULL), FC_OK);
    velocity[0] = 3.0f;   /* the left particle, id 5 */
    CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_NOISE, 0, &violent, NULL, NULL), FC_OK);
    float amplitude = fc_foam_state_amplitude(foam, 5);
    CHECK(amplitude > 1.5f && fc_foam_state_amplitude(foam, 6) == 1.0f);
    int compared[2] = {0, 0}, wrong[2] = {0, 0};
    for (uint32_t row = 0; row < 32; row++)
        for (uint32_t x = 0; x < 48; x++) {
            float c = pixel_f32(&calm, x, row), v = pixel_f32(&violent, x, row);
            int right = x >= 24;
            float scale = right ? 1.0f : amplitude;
            compared[right] += c != 0.0f;
            wrong[right] += fabsf(v - scale * c) > 1e-5f * scale;
        }
    CHECK_MSG(compared[0] > 20 && wrong[0] == 0, "left: %d of %d pixels not scaled by %g", wrong[0], compared[0],
              amplitude);
    CHECK_MSG(compared[1] > 20 && wrong[1] == 0, "right: %d of %d pixels changed", wrong[1], compared[1]);
    fc_image_free(&calm);
    fc_image_free(&violent);
    fc_foam_state_destroy(foam);
}

/* Pixels of `image` that differ from `calm` scaled by each side's amplitude
 * (left half: the particle at -0.6, right half: the one at +0.6), out of
 * those the calm noise covers. */
static void count_unscaled(const fc_image *calm, const fc_image *image, const float scale[2], int compared[2],
                           int wrong[2])
{
    compared[0] = compared[1] = wrong[0] = wrong[1] = 0;
    for (uint32_t row = 0; row < calm->height; row++)
        for (uint32_t x = 0; x < calm->width; x++) {
            float c = pixel_f32(calm, x, row), v = pixel_f32(image, x, row);
            int right = x >= calm->width / 2;
            compared[right] += c != 0.0f;
            wrong[right] += fabsf(v - scale[right] * c) > 1e-5f * scale[right];
        }
}

/* Uploads `frame`, gives it `amplitude` (frame order; NULL: none, so calm)
 * and renders its noise; then checks it against `calm` scaled per side. */
static void check_amplitudes(render_fixture *f, const fc_frame *frame, const float *amplitude, const fc_image *calm,
                             const float scale[2], const char *what)
{
    fc_settings settings = noise_settings(1.0f);
    fc_camera cam = axis_camera(3.0, 48, 32);
    fc_image image = {0};
    CHECK_CODE(fc_pipeline_upload(f->pipeline, frame, NULL, NULL), FC_OK);
    if (amplitude)
        CHECK_CODE(fc_pipeline_set_amplitudes(f->pipeline, amplitude, frame->count, NULL), FC_OK);
    CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_NOISE, 0, &image, NULL, NULL), FC_OK);
    int compared[2], wrong[2];
    count_unscaled(calm, &image, scale, compared, wrong);
    CHECK_MSG(compared[0] > 20 && compared[1] > 20 && wrong[0] == 0 && wrong[1] == 0,
              "%s: %d of %d left, %d of %d right pixels not scaled by %g, %g", what, wrong[0], compared[0], wrong[1],
              compared[1], (double)scale[0], (double)scale[1]);
    fc_image_free(&image);
}

/* Records and amplitudes are written in draw order, densest first: a second
 * frame whose densities reverse that order must move both with the
 * particles, an upload without amplitudes must be calm again, and a frame of
 * positions alone must get its own records back after frames with ids. */
static void test_attributes_follow_a_new_order(render_fixture *f)
{
    float positions[6] = {-0.6f, 0.0f, 0.0f, 0.6f, 0.0f, 0.0f};
    float right_first[2] = {1.0f, 2.0f}, left_first[2] = {2.0f, 1.0f};
    uint32_t ids[2] = {5, 6};
    fc_frame frame = {.count = 2, .positions = positions, .density = right_first, .ids = ids};
    fc_settings settings = noise_settings(1.0f);
    fc_camera cam = axis_camera(3.0, 48, 32);
    fc_image calm = {0};
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, NULL, FC_AOV_NOISE, 0, &calm), FC_OK);
    const float raised_left[2] = {3.0f, 1.0f}, raised_right[2] = {1.0f, 2.0f}, unscaled[2] = {1.0f, 1.0f};
    check_amplitudes(f, &frame, raised_left, &calm, raised_left, "right first, left raised");
    frame.density = left_first;
    check_amplitudes(f, &frame, raised_right, &calm, raised_right, "left first, right raised");
    check_amplitudes(f, &frame, NULL, &calm, unscaled, "left first, no amplitudes");
    frame.density = NULL;
    check_amplitudes(f, &frame, raised_left, &calm, raised_left, "frame order, left raised");

    fc_frame plain = {.count = 2, .positions = positions};
    fc_image plain_calm = {0};
    CHECK_CODE(render_frame(f, &plain, &cam, &settings, NULL, FC_AOV_NOISE, 0, &plain_calm), FC_OK);
    CHECK_MSG(max_difference(&plain_calm, &calm) > 0.1 * max_abs(&calm), "ids 0, 1 noise like ids 5, 6");
    check_amplitudes(f, &plain, raised_right, &plain_calm, raised_right, "positions alone, right raised");
    check_amplitudes(f, &frame, NULL, &calm, unscaled, "ids again");
    check_amplitudes(f, &plain, NULL, &plain_calm, unscaled, "positions alone again");
    fc_image_free(&plain_calm);
    fc_image_free(&calm);
}

/* An upload keeps the frame's order; amplitudes set then must move with
 * their particles when the first render with a density threshold sorts the
 * frame (densest first: the right particle), and only that render sorts. */
static void test_amplitudes_follow_a_later_sort(render_fixture *f)
{
    float positions[6] = {-0.6f, 0.0f, 0.0f, 0.6f, 0.0f, 0.0f};
    float right_first[2] = {1.0f, 2.0f};
    uint32_t ids[2] = {5, 6};
    fc_frame frame = {.count = 2, .positions = positions, .density = right_first, .ids = ids};
    fc_settings settings = noise_settings(1.0f);
    fc_camera cam = axis_camera(3.0, 48, 32);
    fc_image calm = {0}, raised = {0};
    const uint64_t *sorts = &fc_pipeline_particle_attributes(f->pipeline)->density_sorts;
    uint64_t sorts_before = *sorts;
    CHECK_CODE(render_frame(f, &frame, &cam, &settings, NULL, FC_AOV_NOISE, 0, &calm), FC_OK);
    const float raised_left[2] = {3.0f, 1.0f};
    CHECK_CODE(fc_pipeline_set_amplitudes(f->pipeline, raised_left, 2, NULL), FC_OK);
    CHECK(*sorts == sorts_before);
    settings.density_threshold = 0.5f;   /* below both densities: no spray, only the order changes */
    for (int render = 0; render < 2; render++) {
        CHECK_CODE(fc_pipeline_render(f->pipeline, &cam, &settings, FC_AOV_NOISE, 0, &raised, NULL, NULL), FC_OK);
        CHECK_MSG(*sorts == sorts_before + 1, "render %d: %llu sorts, expected 1", render,
                  (unsigned long long)(*sorts - sorts_before));
        int compared[2], wrong[2];
        count_unscaled(&calm, &raised, raised_left, compared, wrong);
        CHECK_MSG(compared[0] > 20 && compared[1] > 20 && wrong[0] == 0 && wrong[1] == 0,
                  "render %d: %d of %d left, %d of %d right pixels not scaled by 3, 1", render, wrong[0],
                  compared[0], wrong[1], compared[1]);
    }
    fc_image_free(&raised);
    fc_image_free(&calm);
}

/* Thousands of strided ids grow the tables; every third particle jumps. */
static void test_foam_many_particles(render_fixture *f)
{
    enum { MANY = 5000 };
    fc_foam_state *foam = NULL;
    CHECK_CODE(fc_foam_state_create(&foam, NULL), FC_OK);
    float *positions = calloc(3 * MANY, sizeof(float)), *velocity = calloc(3 * MANY, sizeof(float));
    uint32_t *ids = malloc(MANY * sizeof(uint32_t));
    if (foam && positions && velocity && ids) {
        for (uint32_t i = 0; i < MANY; i++) {
            ids[i] = i << 12;   /* multiples of 4096: the worst case for a hash taking low bits */
            positions[3 * i] = (float)i * 1e-3f;
        }
        fc_settings settings = foam_settings();
        fc_frame frame = {.count = MANY, .positions = positions, .velocity = velocity, .ids = ids};
        CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
        for (uint32_t i = 0; i < MANY; i += 3)
            velocity[3 * i + 1] = 1.0f;
        CHECK_CODE(advance(f, foam, &frame, &settings), FC_OK);
        int wrong = 0;
        for (uint32_t i = 0; i < MANY; i++)
            wrong += (fc_foam_state_amplitude(foam, ids[i]) > 1.0f) != (i % 3 == 0);
        CHECK_MSG(wrong == 0, "%d particles with the wrong amplitude", wrong);
    }
    free(positions);
    free(velocity);
    free(ids);
    fc_foam_state_destroy(foam);
}

static void test_foam_usage_errors(render_fixture *f)
{
    fc_foam_state *foam = NULL;
    CHECK_CODE(fc_foam_state_create(&foam, NULL), FC_OK);
    fc_settings settings = foam_settings();
    float position[3] = {0};
    fc_frame one = {.count = 1, .positions = position}, none = {0};
    CHECK_CODE(fc_pipeline_upload(f->pipeline, &one, NULL, NULL), FC_OK);
    fc_error err = {0};
    CHECK_CODE(fc_foam_state_advance(foam, f->pipeline, &none, &settings, &err), FC_ERR_USAGE);
    CHECK(strstr(err.message, "uploaded") != NULL);
    CHECK_CODE(fc_foam_state_advance(NULL, f->pipeline, &one, &settings, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_foam_state_create(NULL, &err), FC_ERR_USAGE);
    fc_foam_state_destroy(foam);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    test_off_and_linear(&f);
    test_pattern_moves_with_particles(&f);
    test_pattern_follows_ids(&f);
    test_foam_raise_and_decay(&f);
    test_foam_scales_noise(&f);
    test_attributes_follow_a_new_order(&f);
    test_amplitudes_follow_a_later_sort(&f);
    test_foam_many_particles(&f);
    test_foam_usage_errors(&f);
    fixture_close(&f);
    return test_result();
}
