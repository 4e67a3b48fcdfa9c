/* fc_radius.c — estimating a splat radius from the particle spacing.
 *
 * The radius is 0.9 x the median nearest-neighbour distance of a deterministic
 * sample of at most 4096 particles, where neighbours are searched among *all*
 * particles, exactly. A grid over every particle would scatter writes across
 * memory (seconds for 16M particles); instead only the grid cells around the
 * sampled particles are kept, in a small hash table, and a pass over the
 * positions (cut into ranges on the usable cores, fc_parallel.h) offers each
 * particle to the samples whose cells it falls in. Usually one pass settles
 * every sample.
 *
 * A pilot search among the samples themselves gives each sample an upper
 * bound of its neighbour's distance, and (scaled by the sampling density) the
 * base cell size, which so follows the typical spacing rather than the
 * bounding box: far-away splash particles do not change it. The pilot itself
 * buckets the samples on cells sized by a few probes' spacing, so it costs
 * about a millisecond, not the 6-10 ms of measuring every pair (which it did
 * on every new frame the spray classes see).
 *
 * A sample settles once its neighbour is closer than the cells it searched
 * reach. One that does not gets a second pass on a level of cells (4x wider
 * per level) that reaches the neighbour it already knows, so a sample in a
 * sparse region or far from everything costs no more than that pass. */
#include "fc_frame.h"
#include "fc_parallel.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define SAMPLE_MAX 4096u
/* The pilot: this many samples, spread over the sample, measure their nearest
 * fellow among all samples; their median spacing sizes the cells the pilot
 * buckets every sample on, so that a sample's nearest fellow mostly lies in
 * the 3x3x3 cells around it. */
#define PILOT_PROBES 64
#define PILOT_CELL_PER_SPACING 1.5
/* Pilot cell coordinates are clamped here (a far outlier shares the last
 * cell: a fellow found there is still a real distance, an upper bound). */
#define PILOT_COORD_MAX 0x1p40
#define RADIUS_PER_SPACING 0.9
#define FALLBACK_RADIUS 1.0f
/* The largest radius settings accept (fc_settings_validate): an estimate beyond
 * it would make "auto" fail validation, and beyond FLT_MAX the cast overflows. */
#define MAX_ESTIMATE 1e6
/* A random sample's nearest-neighbour distance is ~0.55 x its mean spacing,
 * so base cells end up ~1.1 mean spacings of the frame wide: most nearest
 * neighbours then lie in the 3x3x3 block of cells around a particle. */
#define CELL_PER_PILOT_SPACING 2.0
/* Level L cells are 4^L base cells wide, aligned with them: a particle's
 * level L cell is its base cell shifted right by 2L bits, so one base cell
 * computation serves every level. The base cell is at least 2^-40 of the
 * bounding box, so at the last level one cell spans the box. */
#define LEVEL_GROWTH_LOG2 2
#define LEVELS 21
#define MIN_BASE_CELL_PER_EXTENT 0x1p-40
#define FIRST_REACH 1
/* Past this many cells of reach, a coarser level is cheaper. */
#define MAX_REACH 3
/* Table keys: level, then each cell coordinate modulo 2^19. Cells 2^19
 * apart share a key: their particles are offered too, which costs time,
 * never exactness. */
#define KEY_AXIS_BITS 19
#define KEY_AXIS_MASK ((UINT64_C(1) << KEY_AXIS_BITS) - 1)
#define KEY_LEVEL_SHIFT (3 * KEY_AXIS_BITS)
#define EMPTY_KEY UINT64_MAX
/* The gate: a 128 KiB bitmap indexed by a hash of (level, cell), set where
 * some sample searches. It stays in L2, so most particles far from every
 * sample are turned away without a miss in the table; the others go on to
 * it. Blocks of 4x4x4 cells in a 32 KiB bitmap let most particles of a 1M
 * frame through (4096 samples' 27 cells touch most blocks): 34 ms for the
 * pass, against 25 with a bit per cell. */
#define GATE_BITS (UINT64_C(1) << 20)
#define GATE_WORDS (GATE_BITS / 64)
#define GATE_BLOCK_LOG2 0

typedef struct grid {
    double lo[3];                /* bounding box minimum: cell (0,0,0) of every level starts here */
    double per_base_cell;        /* 1 / base cell edge */
    double per_cell[LEVELS];     /* 1 / cell edge, per level */
    int64_t dims[LEVELS][3];     /* cells per axis covering the bounding box */
} grid;

/* The cells some samples need, each with the list of those samples. */
typedef struct cell_table {
    uint64_t mask;           /* slots - 1 (a power of two) */
    uint64_t *gate;          /* GATE_WORDS: (level, cell) some sample needs, hashed */
    uint64_t *keys;          /* packed level and cell coordinates, EMPTY_KEY when free */
    uint32_t *list_start;    /* slots + 1: slot s lists samples[list_start[s] .. list_start[s+1]) */
    uint16_t *samples;       /* sample indices (< SAMPLE_MAX) */
    int levels[LEVELS];      /* the levels some sample searches, */
    int n_levels;            /* each once */
} cell_table;

/* The sampled particles and what is known of their nearest neighbours. */
typedef struct search {
    size_t n;
    float positions[SAMPLE_MAX * 3];   /* copied together so the pass over all particles stays in cache */
    double best_sq[SAMPLE_MAX];        /* squared distance to the nearest distinct particle so far */
    int level[SAMPLE_MAX];             /* cell level each sample searches */
    int reach[SAMPLE_MAX];             /* cells searched around the sample's own, per axis and side */
    uint16_t twin_of[SAMPLE_MAX];      /* the first sample at the same position (itself if none) */
    uint16_t pending[SAMPLE_MAX];      /* samples the next pass searches */
    size_t n_pending;
} search;


typedef struct sample_order {
    float position[3];
    uint16_t sample;
} sample_order;

static uint64_t splitmix64(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

static uint64_t cell_key(int level, const int64_t c[3])
{
    return (uint64_t)level << KEY_LEVEL_SHIFT | ((uint64_t)c[0] & KEY_AXIS_MASK) |
           ((uint64_t)c[1] & KEY_AXIS_MASK) << KEY_AXIS_BITS | ((uint64_t)c[2] & KEY_AXIS_MASK) << (2 * KEY_AXIS_BITS);
}

static double distance_sq(const float *a, const float *b)
{
    double dx = (double)a[0] - b[0], dy = (double)a[1] - b[1], dz = (double)a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

/* Distinct: coincident particles (and a sample meeting itself) say nothing about spacing. */
static void offer(double *best_sq, const float *sample, const float *particle)
{
    double d = distance_sq(sample, particle);
    if (d > 0 && d < *best_sq)
        *best_sq = d;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of values[0..n), n > 0; reorders values. */
static double median(double *values, size_t n)
{
    qsort(values, n, sizeof *values, compare_doubles);
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/* ---- Sample and pilot ---- */

/* One particle from each of n equal strata of the index range, at a
 * pseudo-random offset: spread over the whole frame, yet not aligned with
 * the lattice rows that simulation output is often stored in. */
static void choose_sample(const fc_frame *frame, search *s)
{
    s->n = frame->count < SAMPLE_MAX ? (size_t)frame->count : SAMPLE_MAX;
    uint64_t stratum = frame->count / s->n, extra = frame->count % s->n;
    for (size_t i = 0; i < s->n; i++) {
        /* The first `extra` strata hold one particle more. */
        uint64_t begin = i * stratum + (i < extra ? i : extra);
        uint64_t size = stratum + (i < extra);
        uint64_t index = begin + splitmix64(i) % size;
        memcpy(s->positions + 3 * i, frame->positions + 3 * index, 3 * sizeof(float));
        s->best_sq[i] = INFINITY;
        s->level[i] = 0;
        s->reach[i] = FIRST_REACH;
    }
}

static int compare_positions(const void *a, const void *b)
{
    const sample_order *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->position[k] != y->position[k])
            return x->position[k] < y->position[k] ? -1 : 1;
    return (x->sample > y->sample) - (x->sample < y->sample);
}

/* Coincident samples share their nearest distinct neighbour, so only the
 * first of them is searched. Without this, particles piled on one spot (say,
 * inactive ones parked at the origin) would be offered to every sample there. */
static void pend_distinct_samples(search *s)
{
    sample_order order[SAMPLE_MAX];
    for (size_t i = 0; i < s->n; i++) {
        memcpy(order[i].position, s->positions + 3 * i, sizeof order[i].position);
        order[i].sample = (uint16_t)i;
    }
    qsort(order, s->n, sizeof *order, compare_positions);
    s->n_pending = 0;
    for (size_t i = 0; i < s->n; i++) {
        bool twin = i > 0 && memcmp(order[i].position, order[i - 1].position, sizeof order[i].position) == 0;
        uint16_t sample = order[i].sample;
        s->twin_of[sample] = twin ? s->twin_of[order[i - 1].sample] : sample;
        if (!twin)
            s->pending[s->n_pending++] = sample;
    }
}

/* The squared distance from sample i to its nearest distinct fellow sample,
 * measured against every sample (INFINITY when none is distinct). */
static double nearest_fellow_sq(const search *s, size_t i)
{
    double best = INFINITY;
    for (size_t j = 0; j < s->n; j++)
        offer(&best, s->positions + 3 * i, s->positions + 3 * j);
    return best;
}

/* The median nearest-fellow distance of PILOT_PROBES samples spread over
 * the sample; 0 when none has a distinct fellow. */
static double probe_spacing(const search *s)
{
    double nearest[PILOT_PROBES];
    size_t found = 0, probes = s->n < PILOT_PROBES ? s->n : PILOT_PROBES;
    for (size_t k = 0; k < probes; k++) {
        double d = nearest_fellow_sq(s, k * s->n / probes);
        if (isfinite(d))
            nearest[found++] = sqrt(d);
    }
    return found ? median(nearest, found) : 0.0;
}

/* The samples bucketed on cubic cells: a hash of cell coordinates to the
 * samples in the cell. */
typedef struct buckets {
    double lo[3], per_cell;
    uint64_t mask;          /* slots - 1 */
    uint64_t *keys;         /* EMPTY_KEY where free */
    uint32_t *start;        /* slots + 1: slot s holds members[start[s] .. start[s + 1]) */
    uint16_t *members;
} buckets;

static void bucket_cell(const buckets *b, const float *p, int64_t c[3])
{
    for (int k = 0; k < 3; k++) {
        double x = floor(((double)p[k] - b->lo[k]) * b->per_cell);
        c[k] = (int64_t)(x > 0 ? fmin(x, PILOT_COORD_MAX) : 0);
    }
}

static uint64_t bucket_slot(const buckets *b, const int64_t c[3])
{
    uint64_t key = cell_key(0, c);
    uint64_t slot = splitmix64(key) & b->mask;
    while (b->keys[slot] != key && b->keys[slot] != EMPTY_KEY)
        slot = (slot + 1) & b->mask;
    return slot;
}

static void buckets_free(buckets *b)
{
    free(b->keys);
    free(b->start);
    free(b->members);
}

/* Buckets every sample on cells `cell` wide; false when memory runs out. */
static bool buckets_build(buckets *b, const search *s, double cell)
{
    memset(b, 0, sizeof *b);
    uint64_t slots = 64;
    while (slots < 2 * s->n)
        slots *= 2;
    b->mask = slots - 1;
    b->per_cell = 1.0 / cell;
    b->keys = malloc(slots * sizeof *b->keys);
    b->start = calloc(slots + 1, sizeof *b->start);
    b->members = malloc(s->n * sizeof *b->members);
    if (!b->keys || !b->start || !b->members) {
        buckets_free(b);
        return false;
    }
    memset(b->keys, 0xFF, slots * sizeof *b->keys); /* EMPTY_KEY everywhere */
    for (int k = 0; k < 3; k++)
        b->lo[k] = INFINITY;
    for (size_t i = 0; i < s->n; i++)
        for (int k = 0; k < 3; k++)
            b->lo[k] = fmin(b->lo[k], s->positions[3 * i + k]);
    int64_t c[3];
    for (size_t i = 0; i < s->n; i++) {
        bucket_cell(b, s->positions + 3 * i, c);
        uint64_t slot = bucket_slot(b, c);
        b->keys[slot] = cell_key(0, c);
        b->start[slot + 1]++;
    }
    for (uint64_t slot = 0; slot < slots; slot++)
        b->start[slot + 1] += b->start[slot];
    /* Filling advances each slot's start to the next one's; shifting back restores them. */
    for (size_t i = 0; i < s->n; i++) {
        bucket_cell(b, s->positions + 3 * i, c);
        b->members[b->start[bucket_slot(b, c)]++] = (uint16_t)i;
    }
    memmove(b->start + 1, b->start, slots * sizeof *b->start);
    b->start[0] = 0;
    return true;
}

/* The nearest distinct fellow of sample i in the 3x3x3 cells around its
 * own (INFINITY when none is there): a real fellow, so an upper bound of its
 * nearest particle, exact whenever it lies within one cell. */
static double nearest_bucketed_sq(const buckets *b, const search *s, size_t i)
{
    const float *p = s->positions + 3 * i;
    int64_t c[3], at[3];
    bucket_cell(b, p, c);
    double best = INFINITY;
    for (at[2] = c[2] - 1; at[2] <= c[2] + 1; at[2]++)
        for (at[1] = c[1] - 1; at[1] <= c[1] + 1; at[1]++)
            for (at[0] = c[0] - 1; at[0] <= c[0] + 1; at[0]++) {
                if (at[0] < 0 || at[1] < 0 || at[2] < 0)
                    continue;
                uint64_t slot = bucket_slot(b, at);
                for (uint32_t m = b->start[slot]; m < b->start[slot + 1]; m++)
                    offer(&best, p, s->positions + 3 * b->members[m]);
            }
    return best;
}

/* Starts every sample's search from a distinct fellow sample near it (an
 * upper bound of its nearest particle, so the grid passes know how far to
 * look): the nearest in the cells around it, or among all samples when those
 * hold none. Returns the median of those distances, or 0 when none is known.
 * The passes measure in double and end with the exact distances, whatever
 * the bounds. */
static double pilot_spacing(search *s)
{
    double probe = probe_spacing(s);
    buckets b;
    bool bucketed = probe > 0 && buckets_build(&b, s, PILOT_CELL_PER_SPACING * probe);
    for (size_t i = 0; i < s->n; i++) {
        s->best_sq[i] = bucketed ? nearest_bucketed_sq(&b, s, i) : INFINITY;
        if (!isfinite(s->best_sq[i]))
            s->best_sq[i] = nearest_fellow_sq(s, i);
    }
    if (bucketed)
        buckets_free(&b);
    double nearest[SAMPLE_MAX];
    size_t found = 0;
    for (size_t i = 0; i < s->n; i++)
        if (isfinite(s->best_sq[i]))
            nearest[found++] = sqrt(s->best_sq[i]);
    return found ? median(nearest, found) : 0.0;
}

/* ---- Grid ---- */

/* Base cell from the pilot: a sample of n among N particles is (N/n)^(1/3)
 * times sparser per axis than the frame in 3-D. */
static void grid_init(grid *g, const double lo[3], const double hi[3], double pilot, size_t n, uint64_t count)
{
    double max_extent = 0;
    for (int k = 0; k < 3; k++)
        max_extent = fmax(max_extent, hi[k] - lo[k]);
    double base = pilot > 0 ? CELL_PER_PILOT_SPACING * pilot * cbrt((double)n / (double)count)
                            : max_extent / cbrt((double)count);
    base = fmax(base, max_extent * MIN_BASE_CELL_PER_EXTENT);
    g->per_base_cell = 1.0 / base;
    for (int k = 0; k < 3; k++) {
        g->lo[k] = lo[k];
        g->dims[0][k] = (int64_t)floor((hi[k] - lo[k]) * g->per_base_cell) + 1;
    }
    for (int level = 0; level < LEVELS; level++) {
        g->per_cell[level] = ldexp(g->per_base_cell, -LEVEL_GROWTH_LOG2 * level);
        for (int k = 0; k < 3; k++)
            g->dims[level][k] = ((g->dims[0][k] - 1) >> (LEVEL_GROWTH_LOG2 * level)) + 1;
    }
}

static inline void base_cell_of(const grid *g, const float *p, int64_t c[3])
{
    for (int k = 0; k < 3; k++) {
        /* Truncation is floor here: the offset from the box minimum is not negative. */
        double x = ((double)p[k] - g->lo[k]) * g->per_base_cell;
        /* Only rounding can leave the box; clamping keeps the distance bound valid
         * (and keeps a NaN, which callers must not pass, from an undefined conversion). */
        int64_t last = g->dims[0][k] - 1;
        c[k] = !(x >= 0) ? 0 : x > (double)last ? last : (int64_t)x;
    }
}

static void level_cell(const int64_t base[3], int level, int64_t c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = base[k] >> (LEVEL_GROWTH_LOG2 * level);
}

static void cell_of(const grid *g, int level, const float *p, int64_t c[3])
{
    int64_t base[3];
    base_cell_of(g, p, base);
    level_cell(base, level, c);
}


/* ---- Table of needed cells ---- */

/* The slot holding key, or the free slot where it belongs. */
static uint64_t table_slot(const cell_table *t, uint64_t hash, uint64_t key)
{
    uint64_t slot = hash & t->mask;
    while (t->keys[slot] != key && t->keys[slot] != EMPTY_KEY)
        slot = (slot + 1) & t->mask;
    return slot;
}

static uint64_t gate_bit(int level, const int64_t block[3])
{
    return splitmix64(cell_key(level, block)) & (GATE_BITS - 1);
}

static bool gate_open(const cell_table *t, int level, const int64_t c[3])
{
    int64_t block[3];
    for (int k = 0; k < 3; k++)
        block[k] = c[k] >> GATE_BLOCK_LOG2;
    uint64_t bit = gate_bit(level, block);
    return t->gate[bit / 64] >> (bit % 64) & 1;
}

/* Opens the blocks over cells [lo, hi] of `level`. */
static void gate_open_cells(cell_table *t, int level, const int64_t lo[3], const int64_t hi[3])
{
    int64_t block[3];
    for (block[2] = lo[2] >> GATE_BLOCK_LOG2; block[2] <= hi[2] >> GATE_BLOCK_LOG2; block[2]++)
        for (block[1] = lo[1] >> GATE_BLOCK_LOG2; block[1] <= hi[1] >> GATE_BLOCK_LOG2; block[1]++)
            for (block[0] = lo[0] >> GATE_BLOCK_LOG2; block[0] <= hi[0] >> GATE_BLOCK_LOG2; block[0]++) {
                uint64_t bit = gate_bit(level, block);
                t->gate[bit / 64] |= UINT64_C(1) << (bit % 64);
            }
}

static void table_free(cell_table *t)
{
    free(t->gate);
    free(t->keys);
    free(t->list_start);
    free(t->samples);
    memset(t, 0, sizeof *t);
}

typedef enum table_step { COUNT_SAMPLES, LIST_SAMPLES } table_step;

/* Visits every cell within each pending sample's reach (clipped to the
 * grid): counting opens the gate, claims the cells' slots and counts their
 * samples; listing writes the samples down. */
static void visit_needed_cells(cell_table *t, const grid *g, const search *s, table_step step)
{
    for (size_t i = 0; i < s->n_pending; i++) {
        uint16_t sample = s->pending[i];
        int level = s->level[sample];
        int64_t c[3], lo[3], hi[3], at[3];
        cell_of(g, level, s->positions + 3 * sample, c);
        for (int k = 0; k < 3; k++) {
            lo[k] = c[k] - s->reach[sample] < 0 ? 0 : c[k] - s->reach[sample];
            hi[k] = c[k] + s->reach[sample] > g->dims[level][k] - 1 ? g->dims[level][k] - 1 : c[k] + s->reach[sample];
        }
        if (step == COUNT_SAMPLES)
            gate_open_cells(t, level, lo, hi);
        for (at[2] = lo[2]; at[2] <= hi[2]; at[2]++)
            for (at[1] = lo[1]; at[1] <= hi[1]; at[1]++)
                for (at[0] = lo[0]; at[0] <= hi[0]; at[0]++) {
                    uint64_t key = cell_key(level, at), hash = splitmix64(key), slot = table_slot(t, hash, key);
                    if (step == COUNT_SAMPLES) {
                        t->keys[slot] = key;
                        t->list_start[slot + 1]++;
                    } else {
                        t->samples[t->list_start[slot]++] = sample;
                    }
                }
    }
}

static uint64_t cube_cells(int reach)
{
    uint64_t side = 2 * (uint64_t)reach + 1;
    return side * side * side;
}

/* Builds the table of the cells the pending samples need; false when memory runs out. */
static bool table_build(cell_table *t, const grid *g, const search *s)
{
    memset(t, 0, sizeof *t);
    uint64_t visits = 0;
    bool level_used[LEVELS] = {false};
    for (size_t i = 0; i < s->n_pending; i++) {
        visits += cube_cells(s->reach[s->pending[i]]);
        level_used[s->level[s->pending[i]]] = true;
    }
    for (int level = 0; level < LEVELS; level++)
        if (level_used[level])
            t->levels[t->n_levels++] = level;
    uint64_t slots = 64;
    while (slots < 2 * visits)
        slots *= 2;
    t->mask = slots - 1;
    t->gate = calloc(GATE_WORDS, sizeof *t->gate);
    t->keys = malloc(slots * sizeof *t->keys);
    t->list_start = calloc(slots + 1, sizeof *t->list_start);
    t->samples = malloc(visits * sizeof *t->samples);
    if (!t->gate || !t->keys || !t->list_start || !t->samples) {
        table_free(t);
        return false;
    }
    memset(t->keys, 0xFF, slots * sizeof *t->keys); /* EMPTY_KEY everywhere */
    visit_needed_cells(t, g, s, COUNT_SAMPLES);
    for (uint64_t slot = 0; slot < slots; slot++)
        t->list_start[slot + 1] += t->list_start[slot];
    /* Listing advances each slot's start to its end, i.e. to the next slot's start... */
    visit_needed_cells(t, g, s, LIST_SAMPLES);
    /* ...so shifting by one entry restores the starts. */
    memmove(t->list_start + 1, t->list_start, slots * sizeof *t->list_start);
    t->list_start[0] = 0;
    return true;
}

/* ---- Passes ---- */

/* One pass over every particle, cut into ranges (fc_parallel.h): each is
 * offered to the samples listed for its cell at every level in use, the
 * worker keeping its own nearest distances (`best`, SAMPLE_MAX a worker)
 * that the minimum then merges: the same distances however many ran. */
typedef struct scan {
    const fc_frame *frame;
    const grid *g;
    const cell_table *t;
    const search *s;
    double *best;
} scan;

static void scan_range(void *context, unsigned worker, uint64_t begin, uint64_t end)
{
    const scan *j = context;
    const cell_table *t = j->t;
    double *best = j->best + (size_t)worker * SAMPLE_MAX;
    for (uint64_t i = begin; i < end; i++) {
        const float *p = j->frame->positions + 3 * i;
        int64_t base[3];
        base_cell_of(j->g, p, base);
        for (int l = 0; l < t->n_levels; l++) {
            int level = t->levels[l];
            int64_t c[3];
            level_cell(base, level, c);
            if (!gate_open(t, level, c))
                continue;
            uint64_t key = cell_key(level, c), slot = table_slot(t, splitmix64(key), key);
            for (uint32_t k = t->list_start[slot]; k < t->list_start[slot + 1]; k++)
                offer(&best[t->samples[k]], j->s->positions + 3 * t->samples[k], p);
        }
    }
}

static void scan_particles(const fc_frame *frame, const grid *g, const cell_table *t, search *s, double *best,
                           unsigned workers)
{
    for (unsigned w = 0; w < workers; w++)
        memcpy(best + (size_t)w * SAMPLE_MAX, s->best_sq, s->n * sizeof *best);
    scan job = {frame, g, t, s, best};
    fc_parallel_for(frame->count, workers, scan_range, &job);
    for (unsigned w = 1; w < workers; w++)
        for (size_t i = 0; i < s->n; i++)
            best[i] = fmin(best[i], best[(size_t)w * SAMPLE_MAX + i]);
    memcpy(s->best_sq, best, s->n * sizeof *best);
}

/* Cells of `level` between a sample and a neighbour `best_sq` away. */
static double cells_to(const grid *g, int level, double best_sq)
{
    return sqrt(best_sq) * g->per_cell[level];
}

/* Every particle outside the cells within `reach` of a sample's cell is more
 * than reach cell edges away, so a neighbour found within that is final; so
 * is anything found when those cells cover the whole grid. */
static bool settled(const search *s, const grid *g, uint16_t sample)
{
    int level = s->level[sample], reach = s->reach[sample];
    if (cells_to(g, level, s->best_sq[sample]) <= reach)
        return true;
    int64_t c[3];
    cell_of(g, level, s->positions + 3 * sample, c);
    for (int k = 0; k < 3; k++)
        if (c[k] - reach > 0 || c[k] + reach < g->dims[level][k] - 1)
            return false;
    return true;
}

/* Sets a sample with a known neighbour to search the finest level whose
 * cells reach that neighbour within MAX_REACH cells; then it settles. */
static void widen_to_neighbour(search *s, const grid *g, uint16_t sample)
{
    int level = s->level[sample];
    /* The last level spans the box, so the loop stops there at the latest. */
    while (level < LEVELS - 1 && cells_to(g, level, s->best_sq[sample]) > MAX_REACH)
        level++;
    s->level[sample] = level;
    s->reach[sample] = (int)ceil(cells_to(g, level, s->best_sq[sample]));
}

/* Decides what the next pass searches for the samples the last one did not settle. */
static void plan_next_pass(search *s, const grid *g)
{
    size_t unsettled = 0;
    for (size_t i = 0; i < s->n_pending; i++) {
        uint16_t sample = s->pending[i];
        if (settled(s, g, sample))
            continue;
        if (isfinite(s->best_sq[sample])) {
            widen_to_neighbour(s, g, sample);
        } else {
            /* No bound yet (its fellow samples all coincide with it): one level
             * coarser sees 4x as far. The last level spans the box and so settles. */
            s->level[sample]++;
            s->reach[sample] = FIRST_REACH;
        }
        s->pending[unsettled++] = sample;
    }
    s->n_pending = unsettled;
}

/* Finds every sample's exact nearest distinct neighbour; false when memory runs out. */
static bool find_nearest(const fc_frame *frame, const grid *g, search *s)
{
    unsigned workers = fc_parallel_workers(frame->count);
    double *best = malloc((size_t)workers * SAMPLE_MAX * sizeof *best);
    bool found = best != NULL;
    while (found && s->n_pending > 0) {
        cell_table t;
        found = table_build(&t, g, s);
        if (found) {
            scan_particles(frame, g, &t, s, best, workers);
            table_free(&t);
            plan_next_pass(s, g);
        }
    }
    free(best);
    return found;
}

float fc_frame_estimate_radius(const fc_frame *frame)
{
    if (frame->count <= 1)
        return FALLBACK_RADIUS;
    float lo_f[3], hi_f[3];
    fc_frame_bounds(frame, lo_f, hi_f);
    if (lo_f[0] == hi_f[0] && lo_f[1] == hi_f[1] && lo_f[2] == hi_f[2])
        return FALLBACK_RADIUS;
    const double lo[3] = {lo_f[0], lo_f[1], lo_f[2]}, hi[3] = {hi_f[0], hi_f[1], hi_f[2]};

    search *s = malloc(sizeof *s);
    grid *g = malloc(sizeof *g);
    double spacing = 0;
    if (s && g) {
        choose_sample(frame, s);
        pend_distinct_samples(s);
        double pilot = pilot_spacing(s);
        grid_init(g, lo, hi, pilot, s->n, frame->count);
        if (find_nearest(frame, g, s)) {
            /* The box is not a point, so every sample has a distinct neighbour. */
            double distances[SAMPLE_MAX];
            for (size_t i = 0; i < s->n; i++)
                distances[i] = sqrt(s->best_sq[s->twin_of[i]]);
            spacing = median(distances, s->n);
        } else {
            /* Out of memory for the table: the pilot scaled to the full density is the best remaining guess. */
            spacing = pilot * cbrt((double)s->n / (double)frame->count);
        }
    }
    free(s);
    free(g);
    if (!(spacing > 0))
        return FALLBACK_RADIUS;
    return (float)fmin(RADIUS_PER_SPACING * spacing, MAX_ESTIMATE);
}
