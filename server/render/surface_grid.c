/* surface_grid.c — the blocks of surface_grid.h (those whose cells a
 * particle's reach plus one cell meets) and the particles' bins. */
#include "surface_grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

typedef struct block_range {
    uint32_t lo[3], hi[3];   /* inclusive block coordinates a particle reaches */
} block_range;

/* The blocks whose cells meet the box [p - reach - cell, p + reach + cell]:
 * one cell more than the field reaches, so that the block owning a crossing
 * edge's lower end (and a cube's lower corner) is always among them. */
static block_range blocks_reached(const fc_surface_grid *g, const float *p, float reach)
{
    block_range r;
    float block = g->cell * (float)FC_SURFACE_BLOCK;
    for (int a = 0; a < 3; a++) {
        float lo = (p[a] - reach - g->cell - g->origin[a]) / block;
        float hi = (p[a] + reach + g->cell - g->origin[a]) / block;
        r.lo[a] = lo > 0 ? (uint32_t)lo : 0u;
        r.hi[a] = (uint32_t)hi;
    }
    return r;
}

static uint64_t range_blocks(const block_range *r)
{
    return (uint64_t)(r->hi[0] - r->lo[0] + 1) * (r->hi[1] - r->lo[1] + 1) * (r->hi[2] - r->lo[2] + 1);
}

/* Places the origin two cells below the particles' box minus their reach, and
 * checks the box fits the keys' coordinates. */
static fc_code place_grid(const float *positions, uint64_t count, float reach, float cell, fc_surface_grid *g,
                          fc_error *err)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint64_t i = 0; i < count; i++)
        for (int a = 0; a < 3; a++) {
            lo[a] = fminf(lo[a], positions[3 * i + a]);
            hi[a] = fmaxf(hi[a], positions[3 * i + a]);
        }
    g->cell = cell;
    for (int a = 0; a < 3; a++) {
        g->origin[a] = lo[a] - reach - 2.0f * cell;
        double blocks = ((double)hi[a] + reach + 2.0 * cell - g->origin[a]) / ((double)cell * FC_SURFACE_BLOCK);
        if (!(blocks < FC_SURFACE_MAX_BLOCKS_PER_AXIS - 1))
            return fc_error_set(err, FC_ERR_LIMIT,
                                "the surface grid would span %.0f blocks of %u cells along %c, more than %u: "
                                "raise surface_cell",
                                blocks, FC_SURFACE_BLOCK, "xyz"[a], FC_SURFACE_MAX_BLOCKS_PER_AXIS - 1);
    }
    return FC_OK;
}

static uint32_t key_of(uint32_t x, uint32_t y, uint32_t z)
{
    return x | y << FC_SURFACE_KEY_BITS | z << (2 * FC_SURFACE_KEY_BITS);
}

/* Counts the pairs of a particle and a block it reaches (the blocks' marking
 * work, collect_blocks) and checks the budget, which counts 12 bytes a pair
 * (the particle lists they once were), before anything large is allocated. */
static fc_code count_pairs(const fc_surface_grid *g, const float *positions, uint64_t count, float reach,
                           uint64_t *pairs, fc_error *err)
{
    uint64_t n = 0;
    for (uint64_t i = 0; i < count; i++) {
        block_range r = blocks_reached(g, positions + 3 * i, reach);
        n += range_blocks(&r);
    }
    if (n * 12u > FC_SURFACE_GRID_BUDGET || n > UINT32_MAX)
        return fc_error_set(err, FC_ERR_LIMIT,
                            "the surface grid's particle lists would hold %llu entries, over its budget of "
                            "%llu MiB: raise surface_cell",
                            (unsigned long long)n, (unsigned long long)(FC_SURFACE_GRID_BUDGET >> 20));
    *pairs = n;
    return FC_OK;
}

/* The blocks reached (each particle's range, blocks_reached) as bits over the
 * box of block coordinates they span, bit x + span[0] (y + span[1] z): in
 * ascending order of the bits their keys ascend too (x | y << 10 | z << 20),
 * so one scan lists the unique keys in order. At most 1023^3 bits (128 MiB),
 * far less than a pair per particle and block it reaches. */
static fc_code collect_blocks(const float *positions, uint64_t count, float reach, uint64_t n, fc_surface_grid *g,
                              fc_error *err)
{
    uint32_t span[3] = {1, 1, 1};
    for (uint64_t i = 0; i < count; i++) {
        block_range r = blocks_reached(g, positions + 3 * i, reach);
        for (int a = 0; a < 3; a++)
            span[a] = r.hi[a] + 1 > span[a] ? r.hi[a] + 1 : span[a];
    }
    uint64_t bits = (uint64_t)span[0] * span[1] * span[2], words = (bits + 63) / 64;
    uint64_t *reached = calloc(words, sizeof *reached);
    if (!reached)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the surface grid's %llu block flags",
                            (unsigned long long)bits);
    for (uint64_t i = 0; i < count; i++) {
        block_range r = blocks_reached(g, positions + 3 * i, reach);
        for (uint32_t z = r.lo[2]; z <= r.hi[2]; z++)
            for (uint32_t y = r.lo[1]; y <= r.hi[1]; y++)
                for (uint32_t x = r.lo[0]; x <= r.hi[0]; x++) {
                    uint64_t b = x + (uint64_t)span[0] * (y + (uint64_t)span[1] * z);
                    reached[b / 64] |= (uint64_t)1 << (b % 64);
                }
    }
    uint64_t blocks = 0;
    for (uint64_t w = 0; w < words; w++)
        blocks += (uint64_t)__builtin_popcountll(reached[w]);
    fc_code code = FC_OK;
    if (blocks * FC_SURFACE_FIELD_BLOCK_BYTES + n * 12u > FC_SURFACE_GRID_BUDGET)
        code = fc_error_set(err, FC_ERR_LIMIT,
                            "the surface grid would need %llu blocks (%llu MiB), over its budget of %llu MiB: "
                            "raise surface_cell",
                            (unsigned long long)blocks,
                            (unsigned long long)((blocks * FC_SURFACE_FIELD_BLOCK_BYTES + n * 12u) >> 20),
                            (unsigned long long)(FC_SURFACE_GRID_BUDGET >> 20));
    if (code == FC_OK && !(g->block_keys = malloc((blocks ? blocks : 1) * sizeof *g->block_keys)))
        code = fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the surface grid's %llu blocks",
                            (unsigned long long)blocks);
    uint32_t k = 0;
    for (uint64_t w = 0; code == FC_OK && w < words; w++)
        for (uint64_t word = reached[w]; word; word &= word - 1) {
            uint64_t b = w * 64 + (uint64_t)__builtin_ctzll(word);
            uint32_t x = (uint32_t)(b % span[0]), y = (uint32_t)(b / span[0] % span[1]),
                     z = (uint32_t)(b / span[0] / span[1]);
            g->block_keys[k++] = key_of(x, y, z);
        }
    g->block_count = k;
    free(reached);
    return code;
}

/* The bin edge: the field's reach over FC_SURFACE_BIN_SPLIT (a little more,
 * so that rounding cannot put a reaching particle a bin further away), grown until the bins of the grid's
 * box number at most FC_SURFACE_MAX_BINS (a frame spread thinly over a large
 * box gets bigger bins rather than a huge table). */
static void size_bins(fc_surface_grid *g, const float hi[3], float reach)
{
    g->bin = reach * 1.001f / (float)FC_SURFACE_BIN_SPLIT;
    for (;;) {
        double total = 1.0;
        for (int a = 0; a < 3; a++) {
            g->bins[a] = (uint32_t)((hi[a] - g->origin[a]) / g->bin) + 1u;
            total *= g->bins[a];
        }
        if (total <= FC_SURFACE_MAX_BINS)
            return;
        g->bin *= (float)cbrt(total / FC_SURFACE_MAX_BINS) * 1.01f;
    }
}

static uint32_t bin_of(const fc_surface_grid *g, const float *p)
{
    uint32_t c[3];
    for (int a = 0; a < 3; a++) {
        float f = floorf((p[a] - g->origin[a]) / g->bin);
        c[a] = f <= 0.0f ? 0u : f >= (float)(g->bins[a] - 1u) ? g->bins[a] - 1u : (uint32_t)f;
    }
    return c[0] + g->bins[0] * (c[1] + g->bins[1] * c[2]);
}

/* Every particle in exactly one bin: a stable counting sort by bin, so a
 * bin's particles keep their frame order and the lists take one entry per
 * particle whatever the cell size (Rosenberg & Birdwell's lookup, without
 * replicating a particle into every block it reaches). */
static fc_code build_bins(const float *positions, uint64_t count, float reach, fc_surface_grid *g, fc_error *err)
{
    float hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint64_t i = 0; i < count; i++)
        for (int a = 0; a < 3; a++)
            hi[a] = fmaxf(hi[a], positions[3 * i + a]);
    size_bins(g, hi, reach);
    uint64_t bins = (uint64_t)g->bins[0] * g->bins[1] * g->bins[2];
    uint64_t bytes = (uint64_t)g->block_count * FC_SURFACE_FIELD_BLOCK_BYTES + (bins + 1 + count) * 4u;
    if (bytes > FC_SURFACE_GRID_BUDGET)
        return fc_error_set(err, FC_ERR_LIMIT,
                            "the surface grid would need %llu blocks (%llu MiB), over its budget of %llu MiB: "
                            "raise surface_cell",
                            (unsigned long long)g->block_count, (unsigned long long)(bytes >> 20),
                            (unsigned long long)(FC_SURFACE_GRID_BUDGET >> 20));
    g->bin_starts = calloc(bins + 1, sizeof *g->bin_starts);
    g->order = malloc((count ? count : 1) * sizeof *g->order);
    uint32_t *bin_index = malloc((count ? count : 1) * sizeof *bin_index);
    if (!g->bin_starts || !g->order || !bin_index) {
        free(bin_index);
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the surface grid's %llu bins", (unsigned long long)bins);
    }
    for (uint64_t i = 0; i < count; i++) {
        bin_index[i] = bin_of(g, positions + 3 * i);
        g->bin_starts[bin_index[i] + 1]++;
    }
    for (uint64_t b = 0; b < bins; b++)
        g->bin_starts[b + 1] += g->bin_starts[b];
    for (uint64_t i = 0; i < count; i++)
        g->order[g->bin_starts[bin_index[i]]++] = (uint32_t)i;
    /* The fill advanced each start to its bin's end: shift them back. */
    memmove(g->bin_starts + 1, g->bin_starts, bins * sizeof *g->bin_starts);
    g->bin_starts[0] = 0;
    free(bin_index);
    return FC_OK;
}

fc_code fc_surface_grid_build(const float *positions, uint64_t count, float reach, float cell,
                              fc_surface_grid *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    uint64_t n = 0;
    fc_code code = place_grid(positions, count, reach, cell, out, err);
    if (code == FC_OK)
        code = count_pairs(out, positions, count, reach, &n, err);
    if (code != FC_OK)
        return code;
    code = collect_blocks(positions, count, reach, n, out, err);
    if (code == FC_OK)
        code = build_bins(positions, count, reach, out, err);
    if (code != FC_OK)
        fc_surface_grid_free(out);
    return code;
}

void fc_surface_grid_free(fc_surface_grid *grid)
{
    free(grid->block_keys);
    free(grid->bin_starts);
    free(grid->order);
    memset(grid, 0, sizeof *grid);
}
