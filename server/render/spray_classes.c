/* spray_classes.c — see spray_classes.h. */
#include "spray_classes.h"

#include <float.h>
#include <stdbool.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_parallel.h"

/* The table has at most this many slots per particle (a power of two at
 * least as large): beyond it, cells wrap onto each other. */
#define SLOTS_PER_PARTICLE 2u
/* At least 2^2 slots per axis, so the 3 x 3 x 3 cells around any cell fall
 * in 27 different slots. */
#define MIN_AXIS_BITS 2
/* Cell coordinates are clamped here (the offset from the box's minimum is
 * never negative; a far droplet shares the last cells, a distance test away). */
#define MAX_CELL_COORD 0x1p40f

static fc_code out_of_memory(fc_error *err, uint64_t count)
{
    return fc_error_set(err, FC_ERR_NOMEM, "out of memory classifying %llu particles as spray",
                        (unsigned long long)count);
}

static fc_code reserve(fc_spray_classes *c, uint64_t count, uint64_t slots, fc_error *err)
{
    /* Each array is kept as soon as it has grown, so a failure leaks none. */
    if (count > c->capacity) {
        float *keys = realloc(c->keys, count * sizeof *keys);
        if (keys)
            c->keys = keys;
        uint32_t *sorted = keys ? realloc(c->sorted, count * sizeof *sorted) : NULL;
        if (sorted)
            c->sorted = sorted;
        uint32_t *slot_of = sorted ? realloc(c->slot_of, count * sizeof *slot_of) : NULL;
        if (slot_of)
            c->slot_of = slot_of;
        float *gathered = slot_of ? realloc(c->gathered, 3 * count * sizeof *gathered) : NULL;
        if (!gathered)
            return out_of_memory(err, count);
        c->gathered = gathered;
        c->capacity = count;
    }
    if (slots + 1 > c->cell_capacity) {
        uint32_t *starts = realloc(c->cell_start, (slots + 1) * sizeof *starts);
        if (!starts)
            return out_of_memory(err, count);
        c->cell_start = starts;
        c->cell_capacity = slots + 1;
    }
    return FC_OK;
}

static uint32_t ceil_log2(uint64_t n)
{
    uint32_t bits = 0;
    while (bits < 63 && (UINT64_C(1) << bits) < n)
        bits++;
    return bits;
}

/* Slot bits per axis: as many as the box's cells need, so that within the
 * box no two cells share a slot, while the table stays within
 * SLOTS_PER_PARTICLE; a box too large for that (a droplet flung far away)
 * gives up bits on its longest axes, where cells then wrap. */
static void plan_slots(fc_spray_classes *c, const fc_frame *frame, float per_cell)
{
    float hi[3];
    fc_frame_bounds(frame, c->lo, hi);
    uint32_t budget = ceil_log2(SLOTS_PER_PARTICLE * frame->count), total = 0;
    budget = budget < 3 * MIN_AXIS_BITS ? 3 * MIN_AXIS_BITS : budget;
    for (int k = 0; k < 3; k++) {
        float cells = fminf((hi[k] - c->lo[k]) * per_cell, MAX_CELL_COORD) + 1.0f;
        c->bits[k] = ceil_log2((uint64_t)cells);
        c->bits[k] = c->bits[k] < MIN_AXIS_BITS ? MIN_AXIS_BITS : c->bits[k];
        total += c->bits[k];
    }
    while (total > budget) {
        int longest = c->bits[1] > c->bits[0] ? 1 : 0;
        longest = c->bits[2] > c->bits[longest] ? 2 : longest;
        c->bits[longest]--;
        total--;
    }
    c->cells = UINT64_C(1) << total;
}

static void cell_of(const fc_spray_classes *c, const float *p, uint64_t cell[3])
{
    float per_cell = 1.0f / c->support;
    for (int k = 0; k < 3; k++) {
        /* Clamped to [0, MAX_CELL_COORD] (NaN to 0), so truncation is floor. */
        float x = (p[k] - c->lo[k]) * per_cell;
        cell[k] = x > 0.0f ? (uint64_t)(x < MAX_CELL_COORD ? x : MAX_CELL_COORD) : 0;
    }
}

/* The cell's slot: its coordinates modulo 2^bits, packed. Cells a multiple of
 * 2^bits apart share a slot, which costs distance tests, never a wrong count. */
static uint32_t slot_of_cell(const fc_spray_classes *c, uint64_t x, uint64_t y, uint64_t z)
{
    uint64_t mx = (UINT64_C(1) << c->bits[0]) - 1, my = (UINT64_C(1) << c->bits[1]) - 1;
    uint64_t mz = (UINT64_C(1) << c->bits[2]) - 1;
    return (uint32_t)((x & mx) | (y & my) << c->bits[0] | (z & mz) << (c->bits[0] + c->bits[1]));
}

/* Counting sort of the particles by slot into c->sorted, their positions
 * gathered in the same order, so that a cell's particles lie together. */
static void bucket(fc_spray_classes *c, const fc_frame *frame)
{
    memset(c->cell_start, 0, (c->cells + 1) * sizeof *c->cell_start);
    for (uint64_t i = 0; i < frame->count; i++) {
        uint64_t cell[3];
        cell_of(c, frame->positions + 3 * i, cell);
        c->slot_of[i] = slot_of_cell(c, cell[0], cell[1], cell[2]);
        c->cell_start[c->slot_of[i] + 1]++;
    }
    for (uint64_t h = 0; h < c->cells; h++)
        c->cell_start[h + 1] += c->cell_start[h];
    /* Each start advances past its cell's particles as they are placed. */
    for (uint64_t i = 0; i < frame->count; i++) {
        uint32_t at = c->cell_start[c->slot_of[i]]++;
        c->sorted[at] = (uint32_t)i;
        memcpy(c->gathered + 3 * (size_t)at, frame->positions + 3 * i, 3 * sizeof *c->gathered);
    }
    /* The increments moved each start to the next cell's: shift back. */
    memmove(c->cell_start + 1, c->cell_start, c->cells * sizeof *c->cell_start);
    c->cell_start[0] = 0;
}

/* Adds to *found the particles of slot h other than the one at entry `self`
 * within `support` of p; true once there are `enough`. */
static bool count_in_slot(const fc_spray_classes *c, uint32_t self, const float *p, uint32_t h, float support_sq,
                          uint32_t enough, uint32_t *found)
{
    for (uint32_t s = c->cell_start[h]; s < c->cell_start[h + 1]; s++) {
        const float *q = c->gathered + 3 * (size_t)s;
        float d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        if (s != self && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < support_sq && ++*found >= enough)
            return true;
    }
    return false;
}

/* How many other particles lie within the support of the particle at entry
 * `self` of slot `own`, counted up to `enough`: its own cell first, where a
 * particle inside the fluid finds them all, so most particles read one cell,
 * not 27. */
static uint32_t neighbours_of(const fc_spray_classes *c, uint32_t self, uint32_t own, uint32_t enough)
{
    const float *p = c->gathered + 3 * (size_t)self;
    float support_sq = c->support * c->support;
    uint32_t found = 0;
    if (count_in_slot(c, self, p, own, support_sq, enough, &found))
        return found;
    uint32_t cells[27], count = fc_spray_classes_cells_around(c, p, cells);
    for (uint32_t k = 1; k < count; k++)
        if (count_in_slot(c, self, p, cells[k], support_sq, enough, &found))
            return found;
    return found;
}

/* Without densities no density threshold applies: above every one. */
static float surface_key(const fc_frame *frame, uint64_t i)
{
    return frame->density ? fmaxf(frame->density[i], FLT_MIN) : FLT_MAX;
}

/* The classes of the particles in a range of slots, one worker's share:
 * each particle's key is its own, and the worker counts its spray apart. */
typedef struct classify_job {
    fc_spray_classes *c;
    const fc_frame *frame;
    uint32_t enough;
    uint64_t *spray_of;   /* per worker */
} classify_job;

static void classify_slots(void *context, unsigned worker, uint64_t begin, uint64_t end)
{
    const classify_job *j = context;
    fc_spray_classes *c = j->c;
    uint64_t spray = 0;
    for (uint64_t h = begin; h < end; h++)
        for (uint32_t s = c->cell_start[h]; s < c->cell_start[h + 1]; s++) {
            uint32_t i = c->sorted[s];
            bool isolated = neighbours_of(c, s, (uint32_t)h, j->enough) < j->enough;
            spray += isolated;
            c->keys[i] = isolated ? 0.0f : surface_key(j->frame, i);
        }
    j->spray_of[worker] = spray;
}

static void keys_without_spray(fc_spray_classes *c, const fc_frame *frame)
{
    for (uint64_t i = 0; i < frame->count; i++)
        c->keys[i] = surface_key(frame, i);
}

fc_code fc_spray_classes_compute(fc_spray_classes *c, const fc_frame *frame, float support, uint32_t spray_neighbours,
                                 fc_error *err)
{
    fc_code code = reserve(c, frame->count, 0, err);
    if (code != FC_OK)
        return code;
    c->cells = 0;
    c->support = 0.0f;
    /* Frames with their own radii are left to the density threshold: their
     * sizes differ, so one spacing does not tell who is isolated. */
    if (spray_neighbours == 0 || frame->radius || frame->count == 0 || !(support > 0.0f) || !isfinite(support)) {
        keys_without_spray(c, frame);
        return FC_OK;
    }
    c->support = support;
    plan_slots(c, frame, 1.0f / support);
    if ((code = reserve(c, frame->count, c->cells, err)) != FC_OK) {
        c->cells = 0;
        return code;
    }
    bucket(c, frame);
    unsigned workers = fc_parallel_workers(frame->count);
    uint64_t spray_of[FC_PARALLEL_MAX_WORKERS] = {0};
    classify_job job = {c, frame, spray_neighbours, spray_of};
    fc_parallel_for(c->cells, workers, classify_slots, &job);
    uint64_t spray = 0;
    for (unsigned w = 0; w < workers; w++)
        spray += spray_of[w];
    /* Spray is what breaks off a body of fluid: where most particles are
     * isolated (a few particles placed by hand, a sparse point cloud) there is
     * no body, and every particle stays surface. */
    if (2 * spray > frame->count)
        keys_without_spray(c, frame);
    return FC_OK;
}

uint32_t fc_spray_classes_cells_around(const fc_spray_classes *c, const float *p, uint32_t cells[27])
{
    uint64_t home[3];
    cell_of(c, p, home);
    uint32_t count = 0;
    cells[count++] = slot_of_cell(c, home[0], home[1], home[2]);
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++)
                if (dx || dy || dz)
                    cells[count++] = slot_of_cell(c, home[0] + (uint64_t)dx, home[1] + (uint64_t)dy,
                                                  home[2] + (uint64_t)dz);
    return count;
}

float fc_spray_classes_threshold(const fc_settings *settings)
{
    if (settings->density_threshold > 0.0f)
        return settings->density_threshold;
    return settings->spray_neighbours > 0 ? FC_SPRAY_KEY_THRESHOLD : 0.0f;
}

void fc_spray_classes_free(fc_spray_classes *c)
{
    free(c->keys);
    free(c->sorted);
    free(c->slot_of);
    free(c->gathered);
    free(c->cell_start);
    *c = (fc_spray_classes){0};
}
