/* test_surface_solid.c — the field pass's solid blocks (surface_field.comp.glsl)
 * through real GL: a body of fluid at rest, meshed at half-radius cells with
 * both isotropic kernels. A block the pass proves solid (every sample set to
 * the iso value, its sums skipped) must have the field at or above the iso
 * value at every sample, summed here independently in double: else the
 * crossed pass would drop a block the surface crosses, and the mesh would
 * lose its faces there. And the proof must not be idle: every block of the
 * fluid's inside is solid (the field is well above the iso value there), so
 * a block left unproven has some sample within a percent of the iso value or
 * below it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fc_settings.h"
#include "field_check.h"
#include "pipeline_internal.h"
#include "render_fixture.h"
#include "surface_grid.h"
#include "surface_mesher.h"
#include "test_util.h"

#define SPACING 1.0f
#define RADIUS (0.5f * SPACING)   /* a solver's radius: half the spacing */
#define SIDE 20                   /* particles along each edge of the body */

/* SIDE^3 particles one spacing apart, jittered by up to 0.1 spacings (a fixed sequence). */
static float *body_at_rest(uint64_t *count)
{
    float *xyz = malloc((size_t)SIDE * SIDE * SIDE * 3 * sizeof *xyz);
    uint32_t state = 27;
    size_t k = 0;
    for (int z = 0; z < SIDE; z++)
        for (int y = 0; y < SIDE; y++)
            for (int x = 0; x < SIDE; x++) {
                int c[3] = {x, y, z};
                for (int a = 0; a < 3; a++) {
                    state = state * 1664525u + 1013904223u;
                    float jitter = 0.1f * SPACING * ((float)(state >> 8) / 8388608.0f - 1.0f);
                    xyz[k++] = (float)c[a] * SPACING + jitter;
                }
            }
    *count = (uint64_t)SIDE * SIDE * SIDE;
    return xyz;
}

/* The field at x in double, from the particles of every bin within reach. */
static double field_at(const fc_surface_grid *g, const float *xyz, fc_surface_kernel kernel, const double x[3])
{
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        int64_t c = (int64_t)floor((x[a] - g->origin[a]) / g->bin);
        lo[a] = c - (int64_t)FC_SURFACE_BIN_SPLIT - 1 < 0 ? 0 : c - (int64_t)FC_SURFACE_BIN_SPLIT - 1;
        hi[a] = c + (int64_t)FC_SURFACE_BIN_SPLIT + 1 >= (int64_t)g->bins[a] ? (int64_t)g->bins[a] - 1
                                                                            : c + (int64_t)FC_SURFACE_BIN_SPLIT + 1;
    }
    double f = 0.0;
    for (int64_t z = lo[2]; z <= hi[2]; z++)
        for (int64_t y = lo[1]; y <= hi[1]; y++)
            for (int64_t bx = lo[0]; bx <= hi[0]; bx++) {
                uint64_t b = (uint64_t)bx + g->bins[0] * ((uint64_t)y + g->bins[1] * (uint64_t)z);
                for (uint32_t i = g->bin_starts[b]; i < g->bin_starts[b + 1]; i++) {
                    const float *p = xyz + 3 * (size_t)g->order[i];
                    double d2 = 0.0;
                    for (int a = 0; a < 3; a++)
                        d2 += (x[a] - p[a]) * (x[a] - p[a]);
                    f += field_check_weight(kernel, RADIUS, sqrt(d2));
                }
            }
    return f;
}

/* The lowest field in double over the block's samples. */
static double block_minimum(const fc_surface_grid *g, const float *xyz, fc_surface_kernel kernel, uint32_t block)
{
    uint32_t key = g->block_keys[block], mask = FC_SURFACE_MAX_BLOCKS_PER_AXIS - 1u;
    uint32_t base[3] = {(key & mask) * FC_SURFACE_BLOCK, (key >> FC_SURFACE_KEY_BITS & mask) * FC_SURFACE_BLOCK,
                        (key >> 2 * FC_SURFACE_KEY_BITS) * FC_SURFACE_BLOCK};
    double lowest = INFINITY;
    for (uint32_t k = 0; k <= FC_SURFACE_BLOCK; k++)
        for (uint32_t j = 0; j <= FC_SURFACE_BLOCK; j++)
            for (uint32_t i = 0; i <= FC_SURFACE_BLOCK; i++) {
                uint32_t local[3] = {i, j, k};
                double x[3];
                for (int a = 0; a < 3; a++)
                    x[a] = (double)g->origin[a] + (double)(base[a] + local[a]) * g->cell;
                lowest = fmin(lowest, field_at(g, xyz, kernel, x));
            }
    return lowest;
}

static bool all_iso(const float *samples, float iso)
{
    for (uint32_t s = 0; s < FC_SURFACE_BLOCK_SAMPLES; s++)
        if (samples[s] != iso)
            return false;
    return true;
}

static void check_solid_blocks(render_fixture *f, fc_surface_kernel kernel)
{
    uint64_t count;
    float *xyz = body_at_rest(&count);
    fc_frame frame = {.count = count, .positions = xyz};
    fc_settings s;
    fc_settings_default(&s);
    s.radius = RADIUS;
    s.surface_kernel = kernel;
    s.surface_cell = 0.5f;
    const fc_surface_passes *passes = NULL;
    fc_surface_grid g;
    float *field = NULL, iso = 0.0f;
    fc_error err;
    fc_code code = fc_pipeline_surface_passes(f->pipeline, &passes, &err);
    if (code == FC_OK)
        code = fc_surface_mesher_field(passes, &frame, &s, &g, &field, &iso, &err);
    CHECK_MSG(code == FC_OK, "%s", err.message);
    if (code != FC_OK) {
        free(xyz);
        return;
    }
    uint32_t solid = 0, wrong = 0, idle = 0;
    for (uint32_t b = 0; b < g.block_count; b++) {
        bool is_solid = all_iso(field + (size_t)b * FC_SURFACE_BLOCK_SAMPLES, iso);
        double lowest = block_minimum(&g, xyz, kernel, b);
        solid += is_solid;
        wrong += is_solid && !(lowest >= (double)iso);
        idle += !is_solid && lowest >= 1.01 * (double)iso;
    }
    /* The body is 10 blocks of 4 radii a side; its inside, a block in from each face, 8^3 at least. */
    CHECK_MSG(solid >= 512 && wrong == 0 && idle == 0,
              "kernel %d: %u of %u blocks solid, %u of them with a sample below the iso value, %u not solid "
              "though every sample is a percent above it", kernel, solid, g.block_count, wrong, idle);
    printf("kernel %d: %u of %u blocks solid\n", kernel, solid, g.block_count);
    free(field);
    fc_surface_grid_free(&g);
    free(xyz);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    check_solid_blocks(&f, FC_SURFACE_KERNEL_METABALL);
    check_solid_blocks(&f, FC_SURFACE_KERNEL_SPH);
    fixture_close(&f);
    return test_result();
}
