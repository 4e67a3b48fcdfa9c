/* test_up_axis.c — the CLI's up-axis guess (client/cli/up_axis.c) without a
 * daemon: synthetic fluids with a known floor (a splashing pool, fluid heaped
 * against a wall or in a tank corner) turned so that each of the six signed
 * axes is up, shapes with no floor (box, ball, uniform cloud, a few points)
 * that must keep the +z default, the shared sample data (the splash frames
 * and the dam break / drop sets, all +z up, also turned y-up and upside down),
 * and the time a 1M-particle frame takes.
 *
 * Usage: test_up_axis [SHARED_DATA_DIR]; the shared files are skipped when absent. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "particle_reader.h"
#include "point_list.h"
#include "test_util.h"
#include "up_axis.h"

/* ---- building particle sets, +z up ---- */

typedef struct rng {
    uint64_t state;
} rng;

static double uniform(rng *r)
{
    r->state ^= r->state << 13;
    r->state ^= r->state >> 7;
    r->state ^= r->state << 17;
    return (double)(r->state >> 11) / 9007199254740992.0;
}

typedef struct builder {
    point_list points;
    rng random;
} builder;

static void add(builder *b, double x, double y, double z)
{
    point_list_add(&b->points, x, y, z);
}

static double jitter(builder *b, double spacing)
{
    return (uniform(&b->random) - 0.5) * 0.2 * spacing;
}

/* Height of the fluid column over (x, y); below 0 means no fluid there. */
typedef double (*surface_fn)(double x, double y);

/* A jittered lattice filling 0 <= z < surface(x, y) over [0,lx] x [0,ly]: the
 * floor z = 0 is flat, like fluid resting on a boundary. */
static void fill_under(builder *b, double lx, double ly, double h, surface_fn surface)
{
    for (double x = 0.5 * h; x < lx; x += h)
        for (double y = 0.5 * h; y < ly; y += h)
            for (double z = 0.5 * h; z < surface(x, y); z += h)
                add(b, x + jitter(b, h), y + jitter(b, h), z + jitter(b, h));
}

/* Single droplets scattered in a box: spray. */
static void spray(builder *b, int n, const double lo[3], const double hi[3])
{
    for (int i = 0; i < n; i++)
        add(b, lo[0] + (hi[0] - lo[0]) * uniform(&b->random), lo[1] + (hi[1] - lo[1]) * uniform(&b->random),
            lo[2] + (hi[2] - lo[2]) * uniform(&b->random));
}

static double pool_surface(double x, double y)
{
    (void)x;
    (void)y;
    return 0.15;
}

/* A pool filling a 1 x 1 tank, a crown of droplets and a tall thin jet of
 * droplets rising to z = 2 (like the splash frames 16+). */
static void build_splash(builder *b)
{
    const double h = 0.02;
    fill_under(b, 1.0, 1.0, h, pool_surface);
    for (int i = 0; i < 600; i++) {
        double angle = 6.283185307 * uniform(&b->random), r = 0.28 + 0.04 * uniform(&b->random);
        add(b, 0.5 + r * cos(angle), 0.5 + r * sin(angle), 0.15 + 0.2 * uniform(&b->random));
    }
    spray(b, 400, (const double[]){ 0.47, 0.47, 0.15 }, (const double[]){ 0.53, 0.53, 2.0 });
}

/* Sloshed against the wall x = 0: 0.45 deep there, a 0.04 film at x = 1. */
static double heap_surface(double x, double y)
{
    (void)y;
    return 0.04 + 0.41 * (1.0 - x) * (1.0 - x);
}

static void build_heap_on_wall(builder *b)
{
    fill_under(b, 1.0, 0.6, 0.02, heap_surface);
    spray(b, 100, (const double[]){ 0.0, 0.0, 0.1 }, (const double[]){ 0.6, 0.6, 0.7 });
}

/* Piled into the corner x = y = 0 of the tank, thinning to a film. */
static double corner_surface(double x, double y)
{
    double r = sqrt(x * x + y * y);
    return r < 0.8 ? 0.03 + 0.3 * (1.0 - r / 0.8) * (1.0 - r / 0.8) : 0.03;
}

static void build_corner(builder *b)
{
    fill_under(b, 0.9, 0.9, 0.02, corner_surface);
    spray(b, 50, (const double[]){ 0.0, 0.0, 0.05 }, (const double[]){ 0.5, 0.5, 0.5 });
}

/* No floor anywhere: */

static double box_surface(double x, double y)
{
    (void)x;
    (void)y;
    return 0.8;
}

static void build_lattice_box(builder *b)
{
    fill_under(b, 0.8, 0.8, 0.02, box_surface);
}

static void build_random_cube(builder *b)
{
    spray(b, 50000, (const double[]){ 0, 0, 0 }, (const double[]){ 1, 1, 1 });
}

/* Lattice points within radius 25 spacings of the centre. */
static void ball_cut_at(builder *b, int lowest_layer)
{
    const int r = 25;
    const double h = 0.02;
    for (int i = -r; i <= r; i++)
        for (int j = -r; j <= r; j++)
            for (int k = lowest_layer; k <= r; k++)
                if (i * i + j * j + k * k <= r * r)
                    add(b, i * h + jitter(b, h), j * h + jitter(b, h), k * h + jitter(b, h));
}

static void build_ball(builder *b)
{
    ball_cut_at(b, -25);
}

/* A flat facet of radius ~0.2 at the bottom, the ball's tip on top: dense and
 * sparse ends, but the facet does not span the fluid as a floor would. */
static void build_ball_with_facet(builder *b)
{
    ball_cut_at(b, -23);
}

/* ---- turning a +z-up set so that another signed axis is up ---- */

/* A rotation taking +z to sign * axis (and x, y along): axis images of the
 * unit vectors x, y, z as (index, sign) pairs. */
static void turn(float *positions, uint64_t count, int axis, int sign)
{
    /* z -> axis; x -> axis+1; y -> axis+2 (cyclic, so a proper rotation), then a
     * half turn about the image of x for sign -1. */
    int to[3] = { (axis + 1) % 3, (axis + 2) % 3, axis };
    float factor[3] = { 1.0f, (float)sign, (float)sign };
    for (uint64_t i = 0; i < count; i++) {
        float *p = positions + 3 * i, q[3];
        for (int k = 0; k < 3; k++)
            q[to[k]] = factor[k] * p[k];
        memcpy(p, q, sizeof q);
    }
}

static fc_up_guess guess(const float *positions, uint64_t count)
{
    fc_frame frame = { .count = count, .positions = (float *)positions };
    fc_up_guess g;
    fc_error err;
    CHECK_CODE(fc_up_axis_guess(&frame, &g, &err), FC_OK);
    return g;
}

static void describe(const char *what, const fc_up_guess *g)
{
    printf("%-38s -> %s %s (contrast, ends, spans: x %+.2f %u/%u %.2f/%.2f  y %+.2f %u/%u %.2f/%.2f"
           "  z %+.2f %u/%u %.2f/%.2f)\n",
           what, fc_up_axis_name(g->axis, g->sign), g->from_particles ? "guessed" : "default",
           (double)g->contrast[0], g->end_count[0][0], g->end_count[0][1], (double)g->end_span[0][0],
           (double)g->end_span[0][1], (double)g->contrast[1], g->end_count[1][0], g->end_count[1][1],
           (double)g->end_span[1][0], (double)g->end_span[1][1], (double)g->contrast[2], g->end_count[2][0],
           g->end_count[2][1], (double)g->end_span[2][0], (double)g->end_span[2][1]);
}

/* The set, turned to each of the six signed axes in turn, is guessed right. */
static void check_all_turns(const char *name, void (*build)(builder *))
{
    for (int axis = 0; axis < 3; axis++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            builder b = { .random = { 0x9e3779b97f4a7c15ull } };
            build(&b);
            turn(b.points.positions, b.points.count, axis, sign);
            fc_up_guess g = guess(b.points.positions, b.points.count);
            char what[64];
            snprintf(what, sizeof what, "%s, %s up", name, fc_up_axis_name(axis, sign));
            describe(what, &g);
            CHECK_MSG(g.from_particles && g.axis == axis && g.sign == sign, "%s: guessed %s", what,
                      fc_up_axis_name(g.axis, g.sign));
            free(b.points.positions);
        }
    }
}

/* No floor: the default +z, marked as such, however the set is turned. */
static void check_no_floor(const char *name, void (*build)(builder *))
{
    for (int axis = 0; axis < 3; axis++) {
        builder b = { .random = { 0x2545f4914f6cdd1dull } };
        build(&b);
        turn(b.points.positions, b.points.count, axis, 1);
        fc_up_guess g = guess(b.points.positions, b.points.count);
        char what[64];
        snprintf(what, sizeof what, "%s, turned %s", name, fc_up_axis_name(axis, 1));
        describe(what, &g);
        CHECK_MSG(!g.from_particles && g.axis == 2 && g.sign == 1, "%s: guessed %s", what,
                  fc_up_axis_name(g.axis, g.sign));
        free(b.points.positions);
    }
}

static void test_synthetic_floors(void)
{
    check_all_turns("splashing pool with a jet", build_splash);
    check_all_turns("fluid heaped against a wall", build_heap_on_wall);
    check_all_turns("fluid piled in a tank corner", build_corner);
}

static void test_no_floor(void)
{
    check_no_floor("jittered lattice box", build_lattice_box);
    check_no_floor("uniform random cube", build_random_cube);
    check_no_floor("lattice ball", build_ball);
    check_no_floor("lattice ball with a flat facet", build_ball_with_facet);
}

static void test_tiny_frames(void)
{
    const float points[] = { 0, 0, 0, 1, 2, 3, 1, 2, 3, 1, 2, 3, 5, 5, 5 };
    const float same[] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };
    uint64_t counts[] = { 0, 1, 2, 5 };
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        fc_up_guess g = guess(points, counts[i]);
        CHECK_MSG(!g.from_particles && g.axis == 2 && g.sign == 1, "%llu points", (unsigned long long)counts[i]);
    }
    fc_up_guess g = guess(same, 3);
    CHECK(!g.from_particles && g.axis == 2 && g.sign == 1);
}

/* A frame larger than the sample: the guess looks at FC_UP_SAMPLE_MAX particles
 * spread over the whole array (a pool stored floor layer first would otherwise
 * look like a slab with no top), so its cost does not grow with the frame. */
static void test_large_frame(void)
{
    builder b = { .random = { 42 } };
    const double h = 0.005;   /* 1.2M particles in the pool */
    fill_under(&b, 1.0, 1.0, h, pool_surface);
    spray(&b, 5000, (const double[]){ 0.4, 0.4, 0.15 }, (const double[]){ 0.6, 0.6, 1.5 });
    turn(b.points.positions, b.points.count, 1, 1);
    fc_up_guess g = guess(b.points.positions, b.points.count);
    char what[64];
    snprintf(what, sizeof what, "%llu-particle pool, +y up", (unsigned long long)b.points.count);
    describe(what, &g);
    CHECK(b.points.count > 1000000);
    /* The guess looks at a bounded sample, never the whole frame: that, not a
     * stopwatch (this suite also runs under ASan on a loaded machine), is what
     * keeps it cheap on a million particles. */
    CHECK(g.sampled == FC_UP_SAMPLE_MAX);
    CHECK(g.from_particles && g.axis == 1 && g.sign == 1);
    free(b.points.positions);
}

/* ---- the shared sample data ---- */

static bool read_if_present(const char *path, fc_frame *frame)
{
    fc_error err;
    FILE *f = fopen(path, "rb");
    if (!f) {
        printf("skipped %s: not present\n", path);
        return false;
    }
    fclose(f);
    CHECK_CODE(fc_read_particles(path, frame, &err), FC_OK);
    return frame->count > 0;
}

/* The file as stored (+z up), turned so +y is up, and turned upside down. */
static void check_file_turns(const char *path, bool expect_floor)
{
    fc_frame frame = { 0 };
    if (!read_if_present(path, &frame))
        return;
    const int axes[3] = { 2, 1, 2 }, signs[3] = { 1, 1, -1 };
    for (int t = 0; t < 3; t++) {
        if (t == 1)
            turn(frame.positions, frame.count, 1, 1);
        if (t == 2) {   /* back from y-up to z-up, then upside down */
            for (uint64_t i = 0; i < frame.count; i++) {
                float *p = frame.positions + 3 * i, q[3] = { p[2], p[0], p[1] };
                memcpy(p, q, sizeof q);
            }
            turn(frame.positions, frame.count, 2, -1);
        }
        fc_up_guess g = guess(frame.positions, frame.count);
        const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
        char what[80];
        snprintf(what, sizeof what, "%.60s, %s up", base, fc_up_axis_name(axes[t], signs[t]));
        describe(what, &g);
        if (expect_floor)
            CHECK_MSG(g.from_particles && g.axis == axes[t] && g.sign == signs[t], "%s: guessed %s", what,
                      fc_up_axis_name(g.axis, g.sign));
        else   /* a floorless block: the default, which its metadata agrees with only as stored */
            CHECK_MSG(!g.from_particles && g.axis == 2 && g.sign == 1, "%s: guessed %s", what,
                      fc_up_axis_name(g.axis, g.sign));
    }
    fc_frame_free(&frame);
}

static void test_shared_data(const char *dir)
{
    char path[512];
    for (int i = 0; i < 24; i++) {
        snprintf(path, sizeof path, "%s/splash/frame_%04d.ply", dir, i);
        check_file_turns(path, true);
    }
    snprintf(path, sizeof path, "%s/drop_64k.f32", dir);
    check_file_turns(path, true);
    /* The dam break's block hovers above its floor: a box, no floor among the particles. */
    snprintf(path, sizeof path, "%s/dambreak_64k.f32", dir);
    check_file_turns(path, false);
}

int main(int argc, char **argv)
{
    test_synthetic_floors();
    test_no_floor();
    test_tiny_frames();
    test_large_frame();
    if (argc > 1)
        test_shared_data(argv[1]);
    return test_result();
}
