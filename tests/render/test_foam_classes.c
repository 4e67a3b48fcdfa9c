/* test_foam_classes.c — the foam classes (foam_classes.h) on the CPU: an
 * isolated particle is spray, never foam; a loose cluster whose particles
 * converge fast is foam; a calm block beside it (at rest, or the whole frame
 * moving as one) has none; a frame without velocities has none. */
#include <stdbool.h>
#include <stdint.h>

#include "anisotropy.h"
#include "foam_classes.h"
#include "spray_classes.h"
#include "test_util.h"

enum { BLOCK = 125, CLUSTER = 27, ISOLATED = 1, COUNT = BLOCK + CLUSTER + ISOLATED };
#define SPACING 0.1f
/* 1.5 spacings apart: loose, yet every particle keeps neighbours within the support. */
#define CLUSTER_SPACING 0.15f
#define CLUSTER_X 2.0f

/* A 5x5x5 block at rest, a 3x3x3 cluster converging on its centre at speed
 * `converge` per unit of distance, one particle far from both; every particle
 * also moves by `drift` along x. */
static void make_frame(float *x, float *v, float converge, float drift)
{
    int n = 0;
    for (int k = 0; k < 5; k++)
        for (int j = 0; j < 5; j++)
            for (int i = 0; i < 5; i++, n++) {
                float p[3] = {(float)i * SPACING, (float)j * SPACING, (float)k * SPACING};
                for (int a = 0; a < 3; a++) {
                    x[3 * n + a] = p[a];
                    v[3 * n + a] = a == 0 ? drift : 0.0f;
                }
            }
    for (int k = -1; k <= 1; k++)
        for (int j = -1; j <= 1; j++)
            for (int i = -1; i <= 1; i++, n++) {
                float d[3] = {(float)i * CLUSTER_SPACING, (float)j * CLUSTER_SPACING, (float)k * CLUSTER_SPACING};
                for (int a = 0; a < 3; a++) {
                    x[3 * n + a] = d[a] + (a == 0 ? CLUSTER_X : 0.0f);
                    v[3 * n + a] = -converge * d[a] + (a == 0 ? drift : 0.0f);
                }
            }
    x[3 * n] = -3.0f;
    x[3 * n + 1] = 0.0f;
    x[3 * n + 2] = 0.0f;
    v[3 * n] = drift + 5.0f;
    v[3 * n + 1] = 0.0f;
    v[3 * n + 2] = 0.0f;
}

static uint64_t foam_in(const fc_foam_classes *f, int first, int count)
{
    uint64_t found = 0;
    for (int i = first; i < first + count; i++)
        found += f->foam[i];
    return found;
}

static void classify(fc_spray_classes *spray, fc_foam_classes *foam, const fc_frame *frame)
{
    CHECK_CODE(fc_spray_classes_compute(spray, frame, fc_anisotropy_support(fc_frame_estimate_radius(frame)), 2, NULL), FC_OK);
    CHECK_CODE(fc_foam_classes_compute(foam, spray, frame, NULL), FC_OK);
}

static void test_converging_cluster_is_foam(void)
{
    float x[3 * COUNT], v[3 * COUNT];
    make_frame(x, v, 10.0f, 0.0f);
    fc_frame frame = {.count = COUNT, .positions = x, .velocity = v};
    fc_spray_classes spray = {0};
    fc_foam_classes foam = {0};
    classify(&spray, &foam, &frame);
    CHECK(spray.keys[BLOCK + CLUSTER] == 0.0f);
    CHECK(!foam.foam[BLOCK + CLUSTER]);
    CHECK_MSG(foam_in(&foam, 0, BLOCK) == 0, "%llu block particles are foam",
              (unsigned long long)foam_in(&foam, 0, BLOCK));
    uint64_t cluster = foam_in(&foam, BLOCK, CLUSTER);
    CHECK_MSG(2 * cluster > CLUSTER, "only %llu of the %d converging particles are foam", (unsigned long long)cluster,
              CLUSTER);
    CHECK(foam.count == cluster);
    /* The same cluster drifting with the whole frame: the differences, not
     * the velocities, make foam. */
    make_frame(x, v, 10.0f, 7.0f);
    classify(&spray, &foam, &frame);
    CHECK(foam_in(&foam, 0, BLOCK) == 0 && foam_in(&foam, BLOCK, CLUSTER) == cluster);
    fc_spray_classes_free(&spray);
    fc_foam_classes_free(&foam);
}

static void test_calm_frames_have_no_foam(void)
{
    float x[3 * COUNT], v[3 * COUNT];
    fc_frame frame = {.count = COUNT, .positions = x, .velocity = v};
    fc_spray_classes spray = {0};
    fc_foam_classes foam = {0};
    for (int moving = 0; moving < 2; moving++) {
        make_frame(x, v, 0.0f, moving ? 3.0f : 0.0f);
        /* The isolated particle moves with the rest. */
        v[3 * (COUNT - 1)] = moving ? 3.0f : 0.0f;
        classify(&spray, &foam, &frame);
        CHECK_MSG(foam.count == 0, "%llu foam particles in a calm frame", (unsigned long long)foam.count);
    }
    /* Without velocities there is no trapped air to measure. */
    make_frame(x, v, 10.0f, 0.0f);
    frame.velocity = NULL;
    classify(&spray, &foam, &frame);
    CHECK(foam.count == 0 && foam_in(&foam, 0, COUNT) == 0);
    /* Spray off: no grid, no foam. */
    frame.velocity = v;
    CHECK_CODE(fc_spray_classes_compute(&spray, &frame, fc_anisotropy_support(fc_frame_estimate_radius(&frame)), 0, NULL), FC_OK);
    CHECK_CODE(fc_foam_classes_compute(&foam, &spray, &frame, NULL), FC_OK);
    CHECK(foam.count == 0);
    fc_spray_classes_free(&spray);
    fc_foam_classes_free(&foam);
}

int main(void)
{
    test_converging_cluster_is_foam();
    test_calm_frames_have_no_foam();
    return test_result();
}
