/* scene.c — the "drop" scene of ../shared/data/gen_particles.py, regenerated in C
 * so benchmarks can go to millions of particles without data files. */
#include "scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"

#define POOL_HALF 1.0f
#define POOL_DEPTH 0.12f
#define DROP_RADIUS 0.3f
#define DROP_Z 0.6f
#define JITTER 0.1f

/* Fluid volume of the scene; the lattice spacing follows from the particle count. */
static float scene_volume(void)
{
    const float pool = (2.0f * POOL_HALF) * (2.0f * POOL_HALF) * POOL_DEPTH;
    const float drop = 4.0f / 3.0f * (float)M_PI * DROP_RADIUS * DROP_RADIUS * DROP_RADIUS;
    return pool + drop;
}

/* xorshift64*: a tiny deterministic generator, so every run benchmarks the same points. */
static float next_unit(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return (float)((*state * 2685821657736338717ull) >> 40) / (float)(1ull << 24);
}

static int inside_scene(float x, float y, float z)
{
    if (fabsf(x) <= POOL_HALF && fabsf(y) <= POOL_HALF && z >= 0.0f && z <= POOL_DEPTH)
        return 1;
    const float dz = z - DROP_Z;
    return x * x + y * y + dz * dz <= DROP_RADIUS * DROP_RADIUS;
}

/* Visits the `total` lattice points inside the scene in a fixed order and, when
 * xyz is given, stores an evenly spread `keep` of them (keep <= total), jittered.
 * Returns the number of lattice points inside the scene. */
static uint64_t fill_lattice(float h, float *xyz, uint64_t keep, uint64_t total)
{
    uint64_t rng = 0x9E3779B97F4A7C15ull;
    uint64_t stored = 0;
    const int nx = (int)floorf(2.0f * POOL_HALF / h);
    const int nz = (int)floorf((DROP_Z + DROP_RADIUS) / h) + 1;
    uint64_t n = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < nx; j++)
            for (int i = 0; i < nx; i++) {
                const float x = -POOL_HALF + (i + 0.5f) * h;
                const float y = -POOL_HALF + (j + 0.5f) * h;
                const float z = (k + 0.5f) * h;
                if (!inside_scene(x, y, z))
                    continue;
                /* point n is kept when it starts a new share of keep/total */
                const int kept = xyz && (n * keep) / total != ((n + 1) * keep) / total;
                if (kept && stored < keep) {
                    xyz[3 * stored + 0] = x + (2.0f * next_unit(&rng) - 1.0f) * JITTER * h;
                    xyz[3 * stored + 1] = y + (2.0f * next_unit(&rng) - 1.0f) * JITTER * h;
                    xyz[3 * stored + 2] = z + (2.0f * next_unit(&rng) - 1.0f) * JITTER * h;
                    stored++;
                }
                n++;
            }
    return n;
}

fc_code bench_scene_drop(uint64_t count, fc_frame *frame, float *spacing, fc_error *err)
{
    memset(frame, 0, sizeof *frame);
    if (count == 0)
        return fc_error_set(err, FC_ERR_USAGE, "scene needs at least one particle");
    /* Start from the spacing that gives `count` points and shrink until the
     * lattice holds at least that many; the surplus is dropped evenly. */
    float h = cbrtf(scene_volume() / (float)count);
    uint64_t total;
    while ((total = fill_lattice(h, NULL, 0, 1)) < count)
        h *= 0.99f;
    fc_code rc = fc_frame_alloc(frame, count, 0, err);
    if (rc != FC_OK)
        return rc;
    fill_lattice(h, frame->positions, count, total);
    *spacing = h;
    return FC_OK;
}

void bench_scene_drop_camera(uint32_t width, uint32_t height, fc_camera *cam)
{
    const fc_camera c = {
        .eye = {2.0f, -2.9f, 1.9f},
        .target = {0.0f, 0.0f, 0.25f},
        .up = {0.0f, 0.0f, 1.0f},
        .fov_y_deg = 40.0f,
        .width = width,
        .height = height,
    };
    *cam = c;
}
