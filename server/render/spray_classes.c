/* spray_classes.c — see spray_classes.h. */
#include "spray_classes.h"

#include <float.h>
#include <stdbool.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "anisotropy.h"
#include "fc_error.h"

/* fc_frame_estimate_radius's radius per nearest-neighbour distance (fc_radius.c). */
#define ESTIMATED_RADIUS_PER_SPACING 0.9f
/* Hashed cells per particle: few collisions, and the table stays small. */
#define CELLS_PER_PARTICLE 2u

static fc_code out_of_memory(fc_error *err, uint64_t count)
{
    return fc_error_set(err, FC_ERR_NOMEM, "out of memory classifying %llu particles as spray",
                        (unsigned long long)count);
}

static fc_code reserve(fc_spray_classes *c, uint64_t count, uint64_t cells, fc_error *err)
{
    if (count > c->capacity) {
        float *keys = realloc(c->keys, count * sizeof *keys);
        if (keys)
            c->keys = keys;
        uint32_t *sorted = keys ? realloc(c->sorted, count * sizeof *sorted) : NULL;
        if (!sorted)
            return out_of_memory(err, count);
        c->sorted = sorted;
        c->capacity = count;
    }
    if (cells + 1 > c->cell_capacity) {
        uint32_t *starts = realloc(c->cell_start, (cells + 1) * sizeof *starts);
        if (!starts)
            return out_of_memory(err, count);
        c->cell_start = starts;
        c->cell_capacity = cells + 1;
    }
    return FC_OK;
}

/* A cell's slot in the table of `cells` (a power of two): cells far apart
 * may share one, which costs distance tests, never a wrong count. */
static uint32_t cell_hash(int64_t x, int64_t y, int64_t z, uint64_t cells)
{
    uint64_t h = (uint64_t)x * 73856093u ^ (uint64_t)y * 19349663u ^ (uint64_t)z * 83492791u;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 32;
    return (uint32_t)(h & (cells - 1));
}

static void cell_of(const float *p, float per_cell, int64_t c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (int64_t)floorf(p[k] * per_cell);
}

/* Counting sort of the particles by hashed cell into c->sorted. */
static void bucket(fc_spray_classes *c, const fc_frame *frame, float per_cell, uint64_t cells)
{
    memset(c->cell_start, 0, (cells + 1) * sizeof *c->cell_start);
    for (uint64_t i = 0; i < frame->count; i++) {
        int64_t cell[3];
        cell_of(frame->positions + 3 * i, per_cell, cell);
        c->cell_start[cell_hash(cell[0], cell[1], cell[2], cells) + 1]++;
    }
    for (uint64_t h = 0; h < cells; h++)
        c->cell_start[h + 1] += c->cell_start[h];
    /* Each start advances past its cell's particles as they are placed. */
    for (uint64_t i = 0; i < frame->count; i++) {
        int64_t cell[3];
        cell_of(frame->positions + 3 * i, per_cell, cell);
        uint32_t h = cell_hash(cell[0], cell[1], cell[2], cells);
        c->sorted[c->cell_start[h]++] = (uint32_t)i;
    }
    /* The increments moved each start to the next cell's: shift back. */
    memmove(c->cell_start + 1, c->cell_start, cells * sizeof *c->cell_start);
    c->cell_start[0] = 0;
}

/* Adds to *found the particles of hashed cell h other than i within `support`
 * of p; true once there are `enough`. */
static bool count_in_cell(const fc_spray_classes *c, const fc_frame *frame, uint64_t i, const float *p, uint32_t h,
                          float support_sq, uint32_t enough, uint32_t *found)
{
    for (uint32_t s = c->cell_start[h]; s < c->cell_start[h + 1]; s++) {
        uint32_t j = c->sorted[s];
        const float *q = frame->positions + 3 * (size_t)j;
        float d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        if (j != i && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < support_sq && ++*found >= enough)
            return true;
    }
    return false;
}

/* How many other particles lie within `support` of particle i, counted up to
 * `enough`: its own cell first, where a particle inside the fluid finds them
 * all, so most particles read one cell, not 27. */
static uint32_t neighbours_of(const fc_spray_classes *c, const fc_frame *frame, uint64_t i, float support,
                              float per_cell, uint64_t cells, uint32_t enough)
{
    const float *p = frame->positions + 3 * i;
    float support_sq = support * support;
    int64_t home[3];
    cell_of(p, per_cell, home);
    uint32_t found = 0, own = cell_hash(home[0], home[1], home[2], cells);
    if (count_in_cell(c, frame, i, p, own, support_sq, enough, &found))
        return found;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                uint32_t h = cell_hash(home[0] + dx, home[1] + dy, home[2] + dz, cells);
                /* The own cell is counted; another cell hashed to its slot holds the same particles. */
                if (h != own && count_in_cell(c, frame, i, p, h, support_sq, enough, &found))
                    return found;
            }
    return found;
}

/* Without densities no density threshold applies: above every one. */
static float surface_key(const fc_frame *frame, uint64_t i)
{
    return frame->density ? fmaxf(frame->density[i], FLT_MIN) : FLT_MAX;
}

fc_code fc_spray_classes_compute(fc_spray_classes *c, const fc_frame *frame, uint32_t spray_neighbours,
                                 fc_error *err)
{
    uint64_t cells = 16;
    while (cells < CELLS_PER_PARTICLE * frame->count)
        cells *= 2;
    fc_code code = reserve(c, frame->count, cells, err);
    if (code != FC_OK)
        return code;
    c->cells = 0;
    c->support = 0.0f;
    float support = FC_ANISOTROPY_SUPPORT_SPACINGS * fc_frame_estimate_radius(frame) / ESTIMATED_RADIUS_PER_SPACING;
    /* Frames with their own radii are left to the density threshold: their
     * sizes differ, so one spacing does not tell who is isolated. */
    if (spray_neighbours == 0 || frame->radius || !(support > 0.0f) || !isfinite(support)) {
        for (uint64_t i = 0; i < frame->count; i++)
            c->keys[i] = surface_key(frame, i);
        return FC_OK;
    }
    float per_cell = 1.0f / support;
    bucket(c, frame, per_cell, cells);
    c->cells = cells;
    c->support = support;
    uint64_t spray = 0;
    for (uint64_t i = 0; i < frame->count; i++) {
        uint32_t n = neighbours_of(c, frame, i, support, per_cell, cells, spray_neighbours);
        spray += n < spray_neighbours;
        c->keys[i] = n < spray_neighbours ? 0.0f : surface_key(frame, i);
    }
    /* Spray is what breaks off a body of fluid: where most particles are
     * isolated (a few particles placed by hand, a sparse point cloud) there is
     * no body, and every particle stays surface. */
    if (2 * spray > frame->count)
        for (uint64_t i = 0; i < frame->count; i++)
            c->keys[i] = surface_key(frame, i);
    return FC_OK;
}

uint32_t fc_spray_classes_cells_around(const fc_spray_classes *c, const float *p, uint32_t cells[27])
{
    int64_t home[3];
    cell_of(p, 1.0f / c->support, home);
    uint32_t own = cell_hash(home[0], home[1], home[2], c->cells), count = 0;
    cells[count++] = own;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                uint32_t h = cell_hash(home[0] + dx, home[1] + dy, home[2] + dz, c->cells);
                bool again = false;
                for (uint32_t k = 0; k < count; k++)
                    again |= cells[k] == h;
                if (!again)
                    cells[count++] = h;
            }
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
    free(c->cell_start);
    *c = (fc_spray_classes){0};
}
