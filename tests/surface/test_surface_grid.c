/* test_surface_grid.c — the surface mesh's particle bins (surface_grid.h), on
 * the CPU: each particle is listed once, in its own bin, in frame order within
 * a bin; every particle within reach of a point lies in the bins the field
 * pass reads around that point (FC_SURFACE_BIN_SPLIT of its own); and a
 * million particles at cells of one radius fit the budget (the per-octant
 * lists before them replicated each particle up to 8 times and did not). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "fc_error.h"
#include "surface_grid.h"
#include "surface_mesher.h"
#include "test_util.h"

#define RADIUS 1.0f
#define REACH (FC_SURFACE_KERNEL_MAX_REACH_RADII * RADIUS)

/* A fixed-seed generator: the same points every run. */
static float next_unit(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (float)(*state >> 8) / (float)(1u << 24);
}

/* n^3 particles 2 radii apart (an SPH fluid's spacing), jittered by a tenth. */
static float *lattice(int n, uint32_t seed)
{
    float *xyz = malloc((size_t)n * n * n * 3 * sizeof *xyz);
    size_t k = 0;
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                int c[3] = {x, y, z};
                for (int a = 0; a < 3; a++)
                    xyz[k++] = 2.0f * RADIUS * ((float)c[a] + 0.2f * (next_unit(&seed) - 0.5f));
            }
    return xyz;
}

static int64_t bin_coordinate(const fc_surface_grid *g, float p, int a)
{
    int64_t c = (int64_t)floorf((p - g->origin[a]) / g->bin);
    return c < 0 ? 0 : c >= (int64_t)g->bins[a] ? (int64_t)g->bins[a] - 1 : c;
}

static uint64_t bin_index(const fc_surface_grid *g, const float *p)
{
    return (uint64_t)bin_coordinate(g, p[0], 0) +
           g->bins[0] * ((uint64_t)bin_coordinate(g, p[1], 1) + g->bins[1] * (uint64_t)bin_coordinate(g, p[2], 2));
}

/* Every particle once, in the bin its position names, ascending within it. */
static void check_bins(const fc_surface_grid *g, const float *xyz, uint64_t count)
{
    uint64_t bins = (uint64_t)g->bins[0] * g->bins[1] * g->bins[2];
    CHECK(g->bin_starts[0] == 0 && g->bin_starts[bins] == count);
    uint8_t *seen = calloc(count, 1);
    uint64_t misplaced = 0, repeated = 0, unordered = 0;
    for (uint64_t b = 0; b < bins; b++)
        for (uint32_t k = g->bin_starts[b]; k < g->bin_starts[b + 1]; k++) {
            uint32_t p = g->order[k];
            repeated += seen[p]++ != 0;
            misplaced += bin_index(g, xyz + 3 * (uint64_t)p) != b;
            unordered += k > g->bin_starts[b] && g->order[k - 1] >= p;
        }
    CHECK(misplaced == 0 && repeated == 0 && unordered == 0);
    free(seen);
}

/* Brute force against the bins: each particle within reach of a point lies
 * in a bin within FC_SURFACE_BIN_SPLIT of the point's own. */
static void check_reach(const fc_surface_grid *g, const float *xyz, uint64_t count, uint32_t seed)
{
    uint64_t missed = 0, reached = 0;
    for (int s = 0; s < 500; s++) {
        float x[3];
        for (int a = 0; a < 3; a++)
            x[a] = g->origin[a] + next_unit(&seed) * (float)g->bins[a] * g->bin;
        for (uint64_t p = 0; p < count; p++) {
            float d2 = 0.0f;
            for (int a = 0; a < 3; a++)
                d2 += (x[a] - xyz[3 * p + a]) * (x[a] - xyz[3 * p + a]);
            if (d2 >= REACH * REACH)
                continue;
            reached++;
            for (int a = 0; a < 3; a++)
                missed += llabs(bin_coordinate(g, xyz[3 * p + a], a) - bin_coordinate(g, x[a], a)) >
                          (int64_t)FC_SURFACE_BIN_SPLIT;
        }
    }
    printf("points near particles: %llu pairs within reach, %llu outside the bins read\n",
           (unsigned long long)reached, (unsigned long long)missed);
    CHECK(reached > 1000 && missed == 0);
}

static void test_small(void)
{
    float *xyz = lattice(20, 7u);
    uint64_t count = 20 * 20 * 20;
    fc_surface_grid g;
    fc_error err;
    CHECK_CODE(fc_surface_grid_build(xyz, count, REACH, 0.5f * RADIUS, &g, &err), FC_OK);
    check_bins(&g, xyz, count);
    check_reach(&g, xyz, count, 11u);
    fc_surface_grid_free(&g);
    free(xyz);
}

/* A million particles (100^3) at cells of 1 radius: within the budget. */
static void test_million(void)
{
    float *xyz = lattice(100, 13u);
    uint64_t count = 100 * 100 * 100;
    fc_surface_grid g;
    fc_error err;
    fc_code code = fc_surface_grid_build(xyz, count, REACH, 1.0f * RADIUS, &g, &err);
    if (code != FC_OK)
        printf("a million particles at 1 r: %s\n", err.message);
    CHECK_CODE(code, FC_OK);
    if (code == FC_OK) {
        printf("a million particles at 1 r: %u blocks, %u x %u x %u bins\n", g.block_count, g.bins[0], g.bins[1],
               g.bins[2]);
        check_bins(&g, xyz, count);
    }
    fc_surface_grid_free(&g);
    free(xyz);
}

int main(void)
{
    test_small();
    test_million();
    return test_result();
}
