/* foam_classes.c — see foam_classes.h. */
#include "foam_classes.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

/* I_ta must pass this share of the frame's rms speed: velocity noise in a
 * near-calm frame stays below it. */
#define FOAM_MIN_SHARE_OF_RMS_SPEED 0.1
/* ... and stand this many standard deviations above the candidates' mean:
 * the few where the flow traps the most air (an impact, a breaking crown),
 * not the whole stirred pool. */
#define FOAM_SPREADS 1.5

static fc_code reserve(fc_foam_classes *f, uint64_t count, fc_error *err)
{
    if (count <= f->capacity)
        return FC_OK;
    uint8_t *foam = realloc(f->foam, count * sizeof *foam);
    if (foam)
        f->foam = foam;
    float *potential = foam ? realloc(f->potential, count * sizeof *potential) : NULL;
    if (potential)
        f->potential = potential;
    uint8_t *company = potential ? realloc(f->company, count * sizeof *company) : NULL;
    if (company)
        f->company = company;
    float *gathered = company ? realloc(f->gathered, 6 * count * sizeof *gathered) : NULL;
    if (!gathered)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory classifying %llu particles as foam",
                            (unsigned long long)count);
    f->gathered = gathered;
    f->capacity = count;
    return FC_OK;
}

/* One neighbour's share of particle i's trapped-air potential: large when
 * the two approach (v_ij against x_ij), zero when they move apart. */
static double trapped_air_term(const float *xi, const float *vi, const float *xj, const float *vj, float support)
{
    double x[3], v[3], xx = 0.0, vv = 0.0, xv = 0.0;
    for (int k = 0; k < 3; k++) {
        x[k] = (double)xi[k] - xj[k];
        v[k] = (double)vi[k] - vj[k];
        xx += x[k] * x[k];
        vv += v[k] * v[k];
        xv += x[k] * v[k];
    }
    if (!(xx > 0.0) || !(vv > 0.0))
        return 0.0;
    double d = sqrt(xx), speed = sqrt(vv);
    double weight = 1.0 - d / support;
    return weight > 0.0 ? speed * (1.0 - xv / (d * speed)) * weight : 0.0;
}

/* What a walk over a particle's neighbours adds up. */
typedef struct neighbour_sums {
    double potential;     /* I_ta */
    uint32_t neighbours;  /* within the support; the walk stops at FC_FOAM_MAX_NEIGHBOURS: inside the body */
    uint32_t foam;        /* of them foam (the second walk, once foam is known) */
} neighbour_sums;

/* Walks the neighbours within the support of the particle in grid slot
 * `self` on the grid of `s`, the cell holding it first, reading positions and
 * velocities gathered in slot order (6 floats a slot: cells are contiguous):
 * with `foam`, counts the foam among them, else sums I_ta, stopping as soon
 * as the particle has FC_FOAM_MAX_NEIGHBOURS (a bulk particle, most of a
 * pool, reads a cell or two). */
static neighbour_sums walk_neighbours(const fc_spray_classes *s, const float *gathered, uint32_t self,
                                      const uint8_t *foam)
{
    const float *p = gathered + 6 * (size_t)self, *v = p + 3;
    float support_sq = s->support * s->support;
    uint32_t cells[27], count = fc_spray_classes_cells_around(s, p, cells);
    neighbour_sums sums = {0.0, 0, 0};
    for (uint32_t c = 0; c < count; c++)
        for (uint32_t slot = s->cell_start[cells[c]]; slot < s->cell_start[cells[c] + 1]; slot++) {
            const float *q = gathered + 6 * (size_t)slot;
            float d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
            if (slot == self || d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= support_sq)
                continue;
            sums.neighbours++;
            if (foam) {
                sums.foam += foam[s->sorted[slot]];
                continue;
            }
            if (sums.neighbours >= FC_FOAM_MAX_NEIGHBOURS)
                return sums;
            sums.potential += trapped_air_term(p, v, q, q + 3, s->support);
        }
    return sums;
}

/* The frame's positions and velocities in the grid's slot order. */
static void gather(const fc_spray_classes *s, const fc_frame *frame, float *gathered)
{
    for (uint64_t slot = 0; slot < frame->count; slot++) {
        uint32_t i = s->sorted[slot];
        for (int k = 0; k < 3; k++) {
            gathered[6 * slot + k] = frame->positions[3 * (size_t)i + k];
            gathered[6 * slot + 3 + k] = frame->velocity[3 * (size_t)i + k];
        }
    }
}

static double rms_speed(const fc_frame *frame)
{
    double sum = 0.0;
    for (uint64_t i = 0; i < 3 * frame->count; i++)
        sum += (double)frame->velocity[i] * frame->velocity[i];
    return sqrt(sum / (double)frame->count);
}

fc_code fc_foam_classes_compute(fc_foam_classes *f, const fc_spray_classes *spray, const fc_frame *frame,
                                fc_error *err)
{
    fc_code code = reserve(f, frame->count, err);
    if (code != FC_OK)
        return code;
    f->count = 0;
    f->threshold = 0.0f;
    if (frame->count > 0) {
        memset(f->foam, 0, frame->count * sizeof *f->foam);
        memset(f->company, 0, frame->count * sizeof *f->company);
    }
    if (!frame->velocity || spray->cells == 0 || frame->count == 0)
        return FC_OK;
    gather(spray, frame, f->gathered);
    /* The candidates' mean and spread of I_ta, in one pass, in the grid's order. */
    double sum = 0.0, sum_sq = 0.0;
    uint64_t candidates = 0;
    for (uint32_t slot = 0; slot < frame->count; slot++) {
        uint32_t i = spray->sorted[slot];
        neighbour_sums sums = {0.0, FC_FOAM_MAX_NEIGHBOURS, 0};
        if (spray->keys[i] != 0.0f)
            sums = walk_neighbours(spray, f->gathered, slot, NULL);
        double ta = sums.potential;
        bool candidate = spray->keys[i] != 0.0f && sums.neighbours < FC_FOAM_MAX_NEIGHBOURS;
        f->potential[i] = candidate ? (float)ta : 0.0f;
        f->foam[i] = candidate;
        candidates += candidate;
        sum += candidate ? ta : 0.0;
        sum_sq += candidate ? ta * ta : 0.0;
    }
    double mean = candidates ? sum / (double)candidates : 0.0;
    double spread = candidates ? sqrt(fmax(sum_sq / (double)candidates - mean * mean, 0.0)) : 0.0;
    double threshold = fmax(mean + FOAM_SPREADS * spread, FOAM_MIN_SHARE_OF_RMS_SPEED * rms_speed(frame));
    for (uint64_t i = 0; i < frame->count; i++) {
        f->foam[i] = f->foam[i] && spread > 0.0 && (double)f->potential[i] > threshold;
        f->count += f->foam[i];
    }
    f->threshold = f->count ? (float)threshold : 0.0f;
    for (uint32_t slot = 0; slot < frame->count; slot++) {
        uint32_t i = spray->sorted[slot];
        f->company[i] = f->foam[i] ? (uint8_t)fmin(walk_neighbours(spray, f->gathered, slot, f->foam).foam, 255.0)
                                   : 0;
    }
    return FC_OK;
}

void fc_foam_classes_free(fc_foam_classes *f)
{
    free(f->foam);
    free(f->potential);
    free(f->company);
    free(f->gathered);
    *f = (fc_foam_classes){0};
}
