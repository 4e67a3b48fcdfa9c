/* test_radius.c — fc_frame_estimate_radius against brute force and analytic spacings.
 * With a file argument (raw float32 xyz, lattice spacing 0.03125) it checks that file instead. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_frame.h"
#include "test_util.h"

#define SAMPLE_SPACING 0.03125
/* Jitter of +-10% per axis moves a neighbour by at most 20% along the lattice axis
 * and 20% across each other axis, so every nearest-neighbour distance lies in
 * [0.8, sqrt(1.2^2 + 2 * 0.2^2)] = [0.8, 1.233] lattice spacings. */
#define JITTER 0.1
#define NN_MIN_PER_SPACING 0.8
#define NN_MAX_PER_SPACING 1.233

typedef struct rng {
    uint64_t state;
} rng;

/* Uniform in [0, 1): a 64-bit LCG, high bits only. */
static double uniform(rng *r)
{
    r->state = r->state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(r->state >> 11) / 9007199254740992.0;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* 0.9 x the median distance to the nearest particle at a different position, over all particles. */
static double brute_force_radius(const fc_frame *f)
{
    double *nn = malloc(f->count * sizeof *nn);
    for (uint64_t i = 0; i < f->count; i++)
        nn[i] = INFINITY;
    for (uint64_t i = 0; i < f->count; i++) {
        const float *a = f->positions + 3 * i;
        for (uint64_t j = i + 1; j < f->count; j++) {
            const float *b = f->positions + 3 * j;
            double dx = (double)a[0] - b[0], dy = (double)a[1] - b[1], dz = (double)a[2] - b[2];
            double d = dx * dx + dy * dy + dz * dz;
            if (d > 0 && d < nn[i])
                nn[i] = d;
            if (d > 0 && d < nn[j])
                nn[j] = d;
        }
    }
    qsort(nn, f->count, sizeof *nn, compare_doubles);
    size_t n = f->count;
    double median = n % 2 ? sqrt(nn[n / 2]) : 0.5 * (sqrt(nn[n / 2 - 1]) + sqrt(nn[n / 2]));
    free(nn);
    return 0.9 * median;
}

static fc_frame make_frame(uint64_t count)
{
    fc_frame f;
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&f, count, 0, &err), FC_OK);
    return f;
}

static void set_point(fc_frame *f, uint64_t i, double x, double y, double z)
{
    f->positions[3 * i] = (float)x;
    f->positions[3 * i + 1] = (float)y;
    f->positions[3 * i + 2] = (float)z;
}

/* nx*ny*nz lattice points of `spacing`, each moved by up to +-jitter*spacing per axis. */
static fc_frame jittered_lattice(int nx, int ny, int nz, double spacing, double jitter, uint64_t seed)
{
    fc_frame f = make_frame((uint64_t)nx * ny * nz);
    rng r = {seed};
    uint64_t i = 0;
    for (int z = 0; z < nz; z++)
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x++, i++)
                set_point(&f, i, spacing * (x + jitter * (2 * uniform(&r) - 1)),
                          spacing * (y + jitter * (2 * uniform(&r) - 1)),
                          spacing * (z + jitter * (2 * uniform(&r) - 1)));
    return f;
}

static void test_degenerate_frames(void)
{
    fc_frame empty = {0};
    CHECK(fc_frame_estimate_radius(&empty) == 1.0f);
    fc_frame one = make_frame(1);
    set_point(&one, 0, 5, 5, 5);
    CHECK(fc_frame_estimate_radius(&one) == 1.0f);
    fc_frame_free(&one);

    fc_frame same = make_frame(50);
    for (int i = 0; i < 50; i++)
        set_point(&same, i, -2, 3, 0.5);
    CHECK(fc_frame_estimate_radius(&same) == 1.0f);
    /* One particle apart from 49 coincident ones: every nearest distinct neighbour is 2 away. */
    set_point(&same, 17, -2, 3, 2.5);
    CHECK_NEAR(fc_frame_estimate_radius(&same), 1.8, 1e-6);
    fc_frame_free(&same);

    /* Particles millions of units apart: the estimate stays a radius settings accept. */
    fc_frame far = make_frame(4);
    for (int i = 0; i < 4; i++)
        set_point(&far, i, 2e6f * (float)i, 0, 0);
    CHECK(fc_frame_estimate_radius(&far) == 1e6f);
    fc_settings s;
    fc_settings_default(&s);
    s.radius = fc_frame_estimate_radius(&far);
    CHECK_CODE(fc_settings_validate(&s, NULL), FC_OK);
    fc_frame_free(&far);

    /* Far more particles than the sample, nearly all coincident: the sample
     * alone shows no spacing, yet the neighbours beyond it are found. */
    fc_frame piled = make_frame(100 * 4096);
    for (uint64_t i = 0; i < piled.count; i++)
        set_point(&piled, i, 0, 0, 0);
    for (int i = 1; i <= 3; i++)
        set_point(&piled, piled.count / 2 + 1000 * i, i, 0, 0);
    CHECK_NEAR(fc_frame_estimate_radius(&piled), 0.9, 1e-6);
    fc_frame_free(&piled);
}

/* Frames of at most 4096 particles are measured whole, so brute force gives the exact answer: to the
 * bit, as the estimate takes the same median of the same double distances (and caps it at 1e6). */
static void check_exact(const char *name, const fc_frame *f)
{
    double expected = brute_force_radius(f);
    float got = fc_frame_estimate_radius(f);
    CHECK_MSG(got == (float)fmin(expected, 1e6), "%s: estimate %.9g, brute force %.9g", name, (double)got, expected);
}

static void test_matches_brute_force_on_awkward_sets(void)
{
    rng r = {42};
    fc_frame uniform_cloud = make_frame(3000);
    for (int i = 0; i < 3000; i++)
        set_point(&uniform_cloud, i, uniform(&r), uniform(&r), uniform(&r));
    check_exact("uniform cloud", &uniform_cloud);
    fc_frame_free(&uniform_cloud);

    /* Counts that are not a multiple of the pilot's 8 lanes: the padding after
     * the samples (infinitely far) must never be anybody's neighbour. */
    static const int odd_counts[] = {2, 3, 5, 7, 9, 4093};
    for (size_t k = 0; k < sizeof odd_counts / sizeof odd_counts[0]; k++) {
        fc_frame odd = make_frame(odd_counts[k]);
        for (int i = 0; i < odd_counts[k]; i++)
            set_point(&odd, i, uniform(&r), uniform(&r), uniform(&r));
        check_exact("uniform cloud, count not a multiple of 8", &odd);
        fc_frame_free(&odd);
    }

    /* A dense cluster, a sparse cube, isolated outliers far away and exact duplicates. */
    fc_frame mixed = make_frame(4000);
    for (int i = 0; i < 2400; i++)
        set_point(&mixed, i, 0.5 + 1e-3 * uniform(&r), 0.5 + 1e-3 * uniform(&r), 0.5 + 1e-3 * uniform(&r));
    for (int i = 2400; i < 3900; i++)
        set_point(&mixed, i, uniform(&r), uniform(&r), uniform(&r));
    for (int i = 3900; i < 3930; i++)
        set_point(&mixed, i, 1e4 * (uniform(&r) - 0.5), 1e4 * (uniform(&r) - 0.5), -1e4 * uniform(&r));
    for (int i = 3930; i < 4000; i++)
        memcpy(mixed.positions + 3 * i, mixed.positions + 3 * (i - 1000), 3 * sizeof(float));
    check_exact("cluster + cube + outliers + duplicates", &mixed);
    fc_frame_free(&mixed);

    fc_frame sheet = jittered_lattice(60, 60, 1, 0.2, 0.3, 7);
    check_exact("jittered sheet", &sheet);
    fc_frame_free(&sheet);

    /* Scales where the pilot's float squares fail: below 1e-22 they underflow (the rows are measured again
     * in double); at 1e21 they overflow (no bound: the grid's coarser levels find the neighbours). A tiny
     * cluster inside a unit cloud mixes both kinds of row in one frame. */
    static const double scales[] = {1e-22, 1e-19, 1e21};
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++) {
        fc_frame scaled = make_frame(1000);
        for (int i = 0; i < 1000; i++)
            set_point(&scaled, i, scales[k] * uniform(&r), scales[k] * uniform(&r), scales[k] * uniform(&r));
        check_exact(k == 0 ? "cloud at 1e-22" : k == 1 ? "cloud at 1e-19" : "cloud at 1e21", &scaled);
        fc_frame_free(&scaled);
    }
    fc_frame specks = make_frame(2000);
    for (int i = 0; i < 2000; i++) {
        double scale = i % 2 ? 1e-20 : 1.0;
        set_point(&specks, i, scale * uniform(&r), scale * uniform(&r), scale * uniform(&r));
    }
    check_exact("unit cloud with a cluster at 1e-20", &specks);
    fc_frame_free(&specks);

    fc_frame line = make_frame(4096);
    double x = 0;
    for (int i = 0; i < 4096; i++, x += 0.01 + uniform(&r))
        set_point(&line, i, x, -x, 1);
    check_exact("irregular line", &line);
    fc_frame_free(&line);
}

/* Larger than the sample: on a perfect lattice every particle's nearest neighbour is one spacing away. */
static void test_perfect_lattices(void)
{
    fc_frame cube = jittered_lattice(40, 40, 40, 0.25, 0, 0);
    CHECK_NEAR(fc_frame_estimate_radius(&cube), 0.9 * 0.25, 1e-6);
    fc_frame_free(&cube);

    fc_frame sheet = jittered_lattice(200, 100, 1, 2.0, 0, 0);
    CHECK_NEAR(fc_frame_estimate_radius(&sheet), 0.9 * 2.0, 1e-5);
    fc_frame_free(&sheet);

    /* Large enough that the scan runs in ranges on several workers where the
     * machine has the cores (fc_parallel.h): a neighbour found by any range counts. */
    fc_frame large = jittered_lattice(64, 64, 64, 0.125, 0, 0);
    CHECK_NEAR(fc_frame_estimate_radius(&large), 0.9 * 0.125, 1e-6);
    fc_frame_free(&large);

    fc_frame line = jittered_lattice(20000, 1, 1, 0.5, 0, 0);
    CHECK_NEAR(fc_frame_estimate_radius(&line), 0.9 * 0.5, 1e-5);
    fc_frame_free(&line);

    /* Isolated outliers far off (some of which get sampled) leave the median where it was. */
    fc_frame with_outliers = make_frame(30 * 30 * 30 + 500);
    fc_frame lattice = jittered_lattice(30, 30, 30, 0.25, 0, 0);
    memcpy(with_outliers.positions, lattice.positions, 3 * lattice.count * sizeof(float));
    for (int i = 0; i < 500; i++)
        set_point(&with_outliers, lattice.count + i, 1e5 + 1e3 * i, -1e4 * i, 3e3);
    CHECK_NEAR(fc_frame_estimate_radius(&with_outliers), 0.9 * 0.25, 1e-6);
    fc_frame_free(&lattice);
    fc_frame_free(&with_outliers);
}

static void test_jittered_lattice(void)
{
    const double spacing = 0.05;
    fc_frame f = jittered_lattice(24, 24, 24, spacing, JITTER, 1234);
    double got = fc_frame_estimate_radius(&f);
    CHECK(got >= 0.9 * NN_MIN_PER_SPACING * spacing && got <= 0.9 * NN_MAX_PER_SPACING * spacing);
    /* The sample's median stays within a few percent of the whole frame's. */
    CHECK_NEAR(got, brute_force_radius(&f), 0.02 * got);
    fc_frame_free(&f);

    /* A million particles: fast, and in the analytic range. */
    fc_frame big = jittered_lattice(100, 100, 100, spacing, JITTER, 99);
    got = fc_frame_estimate_radius(&big);
    CHECK_MSG(got >= 0.9 * NN_MIN_PER_SPACING * spacing && got <= 0.9 * NN_MAX_PER_SPACING * spacing,
              "estimate %g for spacing %g", got, spacing);
    fc_frame_free(&big);
}

static int test_sample_file(const char *path)
{
    FILE *file = fopen(path, "rb");
    CHECK_MSG(file != NULL, "cannot open %s", path);
    if (!file)
        return test_result();
    fseek(file, 0, SEEK_END);
    long bytes = ftell(file);
    rewind(file);
    fc_frame f = make_frame((uint64_t)bytes / 12);
    CHECK(fread(f.positions, 12, f.count, file) == f.count);
    fclose(file);

    double got = fc_frame_estimate_radius(&f);
    double expected = brute_force_radius(&f);
    printf("%s: %llu particles, estimate %.6f, brute force %.6f, 0.9 x spacing %.6f\n", path,
           (unsigned long long)f.count, got, expected, 0.9 * SAMPLE_SPACING);
    CHECK_NEAR(got, expected, 0.02 * expected);
    CHECK(got >= 0.9 * NN_MIN_PER_SPACING * SAMPLE_SPACING && got <= 0.9 * NN_MAX_PER_SPACING * SAMPLE_SPACING);
    CHECK_NEAR(got, 0.9 * SAMPLE_SPACING, 0.15 * 0.9 * SAMPLE_SPACING);
    fc_frame_free(&f);
    return test_result();
}

int main(int argc, char **argv)
{
    if (argc > 1)
        return test_sample_file(argv[1]);
    test_degenerate_frames();
    test_matches_brute_force_on_awkward_sets();
    test_perfect_lattices();
    test_jittered_lattice();
    return test_result();
}
