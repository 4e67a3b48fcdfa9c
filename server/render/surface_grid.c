/* surface_grid.c — the blocks of surface_grid.h (those whose cells a
 * particle's reach plus one cell meets) and their octants' particle lists
 * (the particles whose reach meets the octant's samples). */
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

/* A pair is key << PARTICLE_BITS | particle: a block key (30 bits) or an
 * octant key (block key << 3 | octant, 33 bits) over a particle index of
 * PARTICLE_BITS (FC_SURFACE_MAX_PARTICLES). */
#define PARTICLE_BITS 28u
#define PARTICLE_MASK ((1ull << PARTICLE_BITS) - 1u)

/* Stable LSD radix sort of the pairs by their key's `key_bits`, 8 bits a pass. */
static fc_code sort_pairs(uint64_t *pairs, uint64_t n, unsigned key_bits, fc_error *err)
{
    uint64_t *tmp = malloc((n ? n : 1) * sizeof *tmp);
    if (!tmp)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate %llu surface grid pairs", (unsigned long long)n);
    for (unsigned shift = PARTICLE_BITS; shift < PARTICLE_BITS + key_bits; shift += 8) {
        uint64_t counts[257] = {0};
        for (uint64_t i = 0; i < n; i++)
            counts[((pairs[i] >> shift) & 0xffu) + 1]++;
        for (int d = 0; d < 256; d++)
            counts[d + 1] += counts[d];
        for (uint64_t i = 0; i < n; i++)
            tmp[counts[(pairs[i] >> shift) & 0xffu]++] = pairs[i];
        memcpy(pairs, tmp, n * sizeof *pairs);
    }
    free(tmp);
    return FC_OK;
}

/* Counts the pairs and checks the budget before anything large is allocated. */
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

static void fill_pairs(const fc_surface_grid *g, const float *positions, uint64_t count, float reach,
                       uint64_t *pairs)
{
    uint64_t n = 0;
    for (uint64_t i = 0; i < count; i++) {
        block_range r = blocks_reached(g, positions + 3 * i, reach);
        for (uint32_t z = r.lo[2]; z <= r.hi[2]; z++)
            for (uint32_t y = r.lo[1]; y <= r.hi[1]; y++)
                for (uint32_t x = r.lo[0]; x <= r.hi[0]; x++)
                    pairs[n++] = (uint64_t)key_of(x, y, z) << PARTICLE_BITS | i;
    }
}

/* The sorted block pairs -> the unique block keys. */
static fc_code collect_blocks(const uint64_t *pairs, uint64_t n, fc_surface_grid *g, fc_error *err)
{
    uint64_t blocks = 0;
    for (uint64_t i = 0; i < n; i++)
        blocks += i == 0 || pairs[i] >> PARTICLE_BITS != pairs[i - 1] >> PARTICLE_BITS;
    if (blocks * FC_SURFACE_BLOCK_BYTES + n * 12u > FC_SURFACE_GRID_BUDGET)
        return fc_error_set(err, FC_ERR_LIMIT,
                            "the surface grid would need %llu blocks (%llu MiB), over its budget of %llu MiB: "
                            "raise surface_cell",
                            (unsigned long long)blocks,
                            (unsigned long long)((blocks * FC_SURFACE_BLOCK_BYTES + n * 12u) >> 20),
                            (unsigned long long)(FC_SURFACE_GRID_BUDGET >> 20));
    g->block_keys = malloc((blocks ? blocks : 1) * sizeof *g->block_keys);
    if (!g->block_keys)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the surface grid's %llu blocks",
                            (unsigned long long)blocks);
    uint32_t b = 0;
    for (uint64_t i = 0; i < n; i++)
        if (i == 0 || pairs[i] >> PARTICLE_BITS != pairs[i - 1] >> PARTICLE_BITS)
            g->block_keys[b++] = (uint32_t)(pairs[i] >> PARTICLE_BITS);
    g->block_count = b;
    return FC_OK;
}

/* Along one axis, the octant halves (global index 2 block + half) whose
 * samples a particle's field reaches: samples [lo, hi] (lattice indices). A
 * half's samples are [8 b, 8 b + 3] (lower) or [8 b + 4, 8 b + 8] (upper:
 * the block's upper face too, which is the next block's lower face). */
static uint32_t halves_reached(int64_t lo, int64_t hi, uint32_t out[8])
{
    uint32_t n = 0;
    for (int64_t b = (lo - 8) / 8 > 0 ? (lo - 8) / 8 : 0; b * 8 <= hi; b++)
        for (int64_t h = 0; h < 2; h++) {
            int64_t first = 8 * b + 4 * h, last = h ? 8 * b + 8 : 8 * b + 3;
            if (first <= hi && last >= lo && n < 8)
                out[n++] = (uint32_t)(2 * b + h);
        }
    return n;
}

/* The samples a particle at p reaches along axis a, widened by one sample
 * against rounding. */
static void samples_reached(const fc_surface_grid *g, const float *p, float reach, int a, int64_t *lo, int64_t *hi)
{
    double l = floor(((double)p[a] - reach - g->origin[a]) / g->cell) - 1.0;
    double h = ceil(((double)p[a] + reach - g->origin[a]) / g->cell) + 1.0;
    *lo = l > 0 ? (int64_t)l : 0;
    *hi = (int64_t)h;
}

static uint64_t octant_key(uint32_t hx, uint32_t hy, uint32_t hz)
{
    return (uint64_t)key_of(hx >> 1, hy >> 1, hz >> 1) << 3 | (hx & 1u) | (hy & 1u) << 1 | (hz & 1u) << 2;
}

/* Every (octant, particle) pair, or only their number when pairs is NULL. */
static uint64_t octant_pairs(const fc_surface_grid *g, const float *positions, uint64_t count, float reach,
                             uint64_t *pairs)
{
    uint64_t n = 0;
    for (uint64_t i = 0; i < count; i++) {
        uint32_t halves[3][8], k[3];
        for (int a = 0; a < 3; a++) {
            int64_t lo, hi;
            samples_reached(g, positions + 3 * i, reach, a, &lo, &hi);
            k[a] = halves_reached(lo, hi, halves[a]);
        }
        if (!pairs) {
            n += (uint64_t)k[0] * k[1] * k[2];
            continue;
        }
        for (uint32_t z = 0; z < k[2]; z++)
            for (uint32_t y = 0; y < k[1]; y++)
                for (uint32_t x = 0; x < k[0]; x++)
                    pairs[n++] = octant_key(halves[0][x], halves[1][y], halves[2][z]) << PARTICLE_BITS | i;
    }
    return n;
}

/* The sorted octant pairs -> each octant's list of every block (octants of
 * blocks not in the grid hold no sample and are dropped). */
static fc_code collect_lists(const uint64_t *pairs, uint64_t n, fc_surface_grid *g, fc_error *err)
{
    uint64_t slots = (uint64_t)g->block_count * FC_SURFACE_OCTANTS;
    g->list_starts = malloc((slots + 1) * sizeof *g->list_starts);
    g->list = malloc((n ? n : 1) * sizeof *g->list);
    if (!g->list_starts || !g->list)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the surface grid's lists");
    uint64_t i = 0, kept = 0;
    for (uint64_t s = 0; s < slots; s++) {
        uint64_t key = (uint64_t)g->block_keys[s / FC_SURFACE_OCTANTS] << 3 | (s % FC_SURFACE_OCTANTS);
        while (i < n && pairs[i] >> PARTICLE_BITS < key)
            i++;
        g->list_starts[s] = (uint32_t)kept;
        for (; i < n && pairs[i] >> PARTICLE_BITS == key; i++)
            g->list[kept++] = (uint32_t)(pairs[i] & PARTICLE_MASK);
    }
    g->list_starts[slots] = (uint32_t)kept;
    return FC_OK;
}

/* The octants' lists, within the budget. */
static fc_code build_lists(const float *positions, uint64_t count, float reach, fc_surface_grid *g, fc_error *err)
{
    uint64_t n = octant_pairs(g, positions, count, reach, NULL);
    if (n * 12u + (uint64_t)g->block_count * FC_SURFACE_BLOCK_BYTES > FC_SURFACE_GRID_BUDGET || n > UINT32_MAX)
        return fc_error_set(err, FC_ERR_LIMIT,
                            "the surface grid's particle lists would hold %llu entries, over its budget of "
                            "%llu MiB: raise surface_cell",
                            (unsigned long long)n, (unsigned long long)(FC_SURFACE_GRID_BUDGET >> 20));
    uint64_t *pairs = malloc((n ? n : 1) * sizeof *pairs);
    if (!pairs)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate %llu surface grid pairs", (unsigned long long)n);
    octant_pairs(g, positions, count, reach, pairs);
    fc_code code = sort_pairs(pairs, n, 3 * FC_SURFACE_KEY_BITS + 3, err);
    if (code == FC_OK)
        code = collect_lists(pairs, n, g, err);
    free(pairs);
    return code;
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
    uint64_t *pairs = malloc((n ? n : 1) * sizeof *pairs);
    if (!pairs)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate %llu surface grid pairs", (unsigned long long)n);
    fill_pairs(out, positions, count, reach, pairs);
    code = sort_pairs(pairs, n, 3 * FC_SURFACE_KEY_BITS, err);
    if (code == FC_OK)
        code = collect_blocks(pairs, n, out, err);
    free(pairs);
    if (code == FC_OK)
        code = build_lists(positions, count, reach, out, err);
    if (code != FC_OK)
        fc_surface_grid_free(out);
    return code;
}

void fc_surface_grid_free(fc_surface_grid *grid)
{
    free(grid->block_keys);
    free(grid->list_starts);
    free(grid->list);
    memset(grid, 0, sizeof *grid);
}
