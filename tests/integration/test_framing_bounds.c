/* test_framing_bounds.c — the box the CLI's auto camera frames
 * (client/cli/framing_bounds.c) without a daemon: droplets flung far from a
 * pool are left out and the pool's box is exact; compact fluids (a ball, a
 * pool with a jet rising from it, a handful of points) keep their whole
 * bounding box; a separate drop holding more than the tail fraction is
 * kept however far away; a 1M-particle frame chooses its cuts from the
 * bounded sample; no particles; the union of a sequence; the shared splash
 * frames.
 *
 * Usage: test_framing_bounds [SHARED_DATA_DIR]; the shared files are skipped when absent. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "framing_bounds.h"
#include "particle_reader.h"
#include "point_list.h"
#include "test_util.h"

/* ---- particle sets ---- */

typedef struct builder {
    point_list points;
    uint32_t seed;
} builder;

static void add(builder *b, double x, double y, double z)
{
    point_list_add(&b->points, x, y, z);
}

/* A fixed-seed wobble of +-0.1 spacing, so no two layers are exactly flat. */
static double wobble(builder *b, double spacing)
{
    b->seed = b->seed * 1664525u + 1013904223u;
    return ((b->seed >> 8) / 16777216.0 - 0.5) * 0.2 * spacing;
}

/* An n x n x layers pool of spacing h on z = 0, starting at the origin. */
static void add_pool(builder *b, int n, int layers, double h)
{
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            for (int k = 0; k < layers; k++)
                add(b, (i + 0.5) * h + wobble(b, h), (j + 0.5) * h + wobble(b, h), (k + 0.5) * h + wobble(b, h));
}

/* Lattice points of spacing h within radius r of c. */
static void add_ball(builder *b, const double c[3], double r, double h)
{
    int steps = (int)(r / h);
    for (int i = -steps; i <= steps; i++)
        for (int j = -steps; j <= steps; j++)
            for (int k = -steps; k <= steps; k++)
                if ((i * i + j * j + k * k) * h * h <= r * r)
                    add(b, c[0] + i * h, c[1] + j * h, c[2] + k * h);
}

static fc_frame frame_of(const builder *b)
{
    return (fc_frame){ .count = b->points.count, .positions = b->points.positions };
}

static fc_framing_box framing(const builder *b)
{
    fc_frame f = frame_of(b);
    fc_framing_box box;
    fc_error err;
    CHECK_CODE(fc_framing_box_of(&f, &box, &err), FC_OK);
    return box;
}

/* The framing box is the frame's whole bounding box, nothing left out. */
static void check_whole(const builder *b, const char *what)
{
    fc_frame f = frame_of(b);
    float lo[3], hi[3];
    fc_frame_bounds(&f, lo, hi);
    fc_framing_box box = framing(b);
    for (int k = 0; k < 3; k++)
        CHECK_MSG(box.lo[k] == lo[k] && box.hi[k] == hi[k], "%s: axis %d framed %g..%g, bounds %g..%g", what, k,
                  (double)box.lo[k], (double)box.hi[k], (double)lo[k], (double)hi[k]);
    CHECK_MSG(box.left_out == 0, "%s: %llu left out", what, (unsigned long long)box.left_out);
}

static void check_box_equals(const fc_framing_box *box, const float lo[3], const float hi[3], const char *what)
{
    for (int k = 0; k < 3; k++)
        CHECK_MSG(box->lo[k] == lo[k] && box->hi[k] == hi[k], "%s: axis %d framed %g..%g, expected %g..%g", what, k,
                  (double)box->lo[k], (double)box->hi[k], (double)lo[k], (double)hi[k]);
}

/* ---- tests ---- */

/* A 1 x 1 x 0.14 pool (like the shared splash's) and droplets far above and
 * to the side: the box is exactly the pool's, the droplets counted. */
static void test_droplets_left_out(void)
{
    builder b = { .seed = 1 };
    add_pool(&b, 40, 6, 0.025);
    fc_frame pool = frame_of(&b);
    float lo[3], hi[3];
    fc_frame_bounds(&pool, lo, hi);
    add(&b, 0.5, 0.5, 2.1);
    fc_framing_box box = framing(&b);
    check_box_equals(&box, lo, hi, "pool + droplet at z = 2.1");
    CHECK_MSG(box.left_out == 1, "%llu left out", (unsigned long long)box.left_out);
    for (int i = 0; i < 20; i++)   /* a spray of 20 droplets off to -x, up and out */
        add(&b, -0.3 - 0.05 * i, 0.5, 0.2 + 0.08 * i);
    box = framing(&b);
    check_box_equals(&box, lo, hi, "pool + 21 droplets");
    CHECK_MSG(box.left_out == 21, "%llu left out", (unsigned long long)box.left_out);
    free(b.points.positions);
}

/* Compact fluids keep their whole box, so the camera they had. */
static void test_compact_kept_whole(void)
{
    builder ball = { .seed = 2 };
    add_ball(&ball, (const double[]){ 0, 0, 0 }, 0.5, 0.0625);
    check_whole(&ball, "lattice ball");
    /* A jet: one column of particles 0.02 apart (the pool's spacing is 0.025)
     * rising to 6 times the pool's depth is one body with the pool. */
    builder jet = { .seed = 3 };
    add_pool(&jet, 24, 4, 0.025);
    for (int j = 0; j < 40; j++)
        add(&jet, 0.3, 0.3, 0.1 + 0.02 * (j + 1));
    check_whole(&jet, "pool with a jet");
    /* Fewer than 1 / FC_FRAMING_TAIL particles: no tail to leave out. */
    builder few = { .seed = 4 };
    for (int i = 0; i < 150; i++)
        add(&few, i == 0 ? 100.0 : 0.01 * (i % 10), 0.01 * (i / 10), 0.0);
    check_whole(&few, "150 points, one far away");
    free(ball.points.positions);
    free(jet.points.positions);
    free(few.points.positions);
}

/* A drop holding 2% of the particles, far above the pool, is part of the scene. */
static void test_separate_body_kept(void)
{
    builder b = { .seed = 5 };
    add_pool(&b, 40, 6, 0.025);
    uint64_t pool = b.points.count;
    add_ball(&b, (const double[]){ 0.5, 0.5, 3.0 }, 0.1, 0.025);
    CHECK_MSG(b.points.count - pool > pool / 50, "the drop has %llu particles", (unsigned long long)(b.points.count - pool));
    check_whole(&b, "pool + a drop far above");
    free(b.points.positions);
}

/* 1M particles: the cuts come from FC_FRAMING_SAMPLE_MAX of them, the box
 * from all (the pool's exact top layer), the lone droplet still left out. */
static void test_large_frame(void)
{
    builder b = { .seed = 6 };
    add_pool(&b, 250, 16, 0.004);
    fc_frame pool = frame_of(&b);
    float lo[3], hi[3];
    fc_frame_bounds(&pool, lo, hi);
    add(&b, 0.5, 0.5, 2.0);
    CHECK(b.points.count == 1000001);
    fc_framing_box box = framing(&b);
    CHECK_MSG(box.sampled == FC_FRAMING_SAMPLE_MAX, "sampled %llu", (unsigned long long)box.sampled);
    check_box_equals(&box, lo, hi, "1M-particle pool + droplet");
    CHECK_MSG(box.left_out == 1, "%llu left out", (unsigned long long)box.left_out);
    free(b.points.positions);
}

static void test_empty(void)
{
    const fc_frame none = { .count = 0 };
    fc_framing_box box;
    fc_error err;
    CHECK_CODE(fc_framing_box_of(&none, &box, &err), FC_OK);
    check_box_equals(&box, (const float[]){ 0, 0, 0 }, (const float[]){ 0, 0, 0 }, "no particles");
    CHECK(box.left_out == 0 && box.sampled == 0);
}

static void test_union(void)
{
    fc_framing_box a = { .lo = { 0, 0, 0 }, .hi = { 1, 1, 1 }, .left_out = 3, .sampled = 10 };
    const fc_framing_box b = { .lo = { -1, 0.5f, 0 }, .hi = { 0.5f, 2, 1 }, .left_out = 1, .sampled = 20 };
    fc_framing_box_union(&a, &b);
    check_box_equals(&a, (const float[]){ -1, 0, 0 }, (const float[]){ 1, 2, 1 }, "union");
    CHECK(a.left_out == 3 && a.sampled == 20);
}

/* ---- the shared splash (README: a 1 x 1 m tank, the pool 0.14 m deep, a
 * column of jet droplets up to z = 2.12 in frames 18-23) ---- */

static bool read_if_present(const char *path, fc_frame *frame)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        printf("skipped %s: not present\n", path);
        return false;
    }
    fclose(f);
    fc_error err;
    CHECK_CODE(fc_read_particles(path, frame, &err), FC_OK);
    return frame->count > 0;
}

static void test_splash(const char *dir)
{
    for (int i = 0; i < 24; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/splash/frame_%04d.ply", dir, i);
        fc_frame f = { 0 };
        if (!read_if_present(path, &f))
            return;
        float lo[3], hi[3];
        fc_frame_bounds(&f, lo, hi);
        fc_framing_box box;
        fc_error err;
        CHECK_CODE(fc_framing_box_of(&f, &box, &err), FC_OK);
        printf("frame %2d: z top %.3f of %.3f, %llu of %llu left out\n", i, (double)box.hi[2], (double)hi[2],
               (unsigned long long)box.left_out, (unsigned long long)f.count);
        /* The tank's floor and walls are always framed; at most 0.2% left out. */
        for (int k = 0; k < 3; k++)
            CHECK_MSG(box.lo[k] == lo[k] && (k == 2 || box.hi[k] == hi[k]), "frame %d: axis %d", i, k);
        CHECK_MSG(box.left_out <= f.count / 500, "frame %d: %llu left out", i, (unsigned long long)box.left_out);
        if (i == 0)   /* the falling drop (5% of the particles) is framed whole */
            CHECK_MSG(box.hi[2] == hi[2] && box.left_out == 0, "frame 0: z top %g", (double)box.hi[2]);
        if (i >= 18)  /* the jet's droplets far above the tank's 0.6 m walls are not */
            CHECK_MSG(box.hi[2] < 1.0f && hi[2] > 1.3f, "frame %d: z top %g of %g", i, (double)box.hi[2],
                      (double)hi[2]);
        fc_frame_free(&f);
    }
}

int main(int argc, char **argv)
{
    test_droplets_left_out();
    test_compact_kept_whole();
    test_separate_body_kept();
    test_large_frame();
    test_empty();
    test_union();
    if (argc > 1)
        test_splash(argv[1]);
    return test_result();
}
