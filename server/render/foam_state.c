/* foam_state.c — per-particle noise amplitude across frames (van der Laan et
 * al. 2009, §3.4, eq. 12; the patent's amplitude levels): a particle whose
 * velocity jumps by more than foam_tau is raised to a turbulent amplitude,
 * which cools down geometrically by foam_decay per frame.
 *
 * The state is an open-addressing hash map from id to (last velocity, raise).
 * Each frame builds a fresh table from the previous one, so particles that
 * left the simulation drop out without deletions, and the work is O(N). The
 * two tables and the amplitude array are reused: no allocation per frame
 * once they have grown to the largest frame. */
#include "foam_state.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "pipeline_internal.h"

/* A jump raises the amplitude multiplier from 1 (calm) to 1 + this
 * (turbulent): the second of the patent's amplitude levels, strong enough
 * that foam stands out from the calm surface's noise. */
#define TURBULENT_RAISE 3.0f
/* Tables stay at most half full, so probes are short. */
#define LOAD_FACTOR_INVERSE 2

typedef struct foam_entry {
    uint32_t id;
    uint32_t used;         /* 0 = empty slot */
    float velocity[3];     /* in the frame the entry was made */
    float raise;           /* amplitude multiplier - 1 */
} foam_entry;

struct fc_foam_state {
    foam_entry *tables[2];   /* [current] holds the last frame; the other is scratch */
    int current;
    size_t capacity;         /* slots per table, a power of two */
    float *amplitude;        /* per particle of the last frame, frame order */
    uint64_t amplitude_capacity;
};

fc_code fc_foam_state_create(fc_foam_state **out, fc_error *err)
{
    if (!out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_foam_state_create: no output");
    *out = calloc(1, sizeof **out);
    if (!*out)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the foam state");
    return FC_OK;
}

void fc_foam_state_destroy(fc_foam_state *s)
{
    if (!s)
        return;
    free(s->tables[0]);
    free(s->tables[1]);
    free(s->amplitude);
    free(s);
}

/* Fibonacci hashing: the multiplication spreads consecutive or strided ids
 * over all 32 bits, and scaling by the capacity keeps the high bits, where
 * the spreading is best. */
static size_t slot_of(uint32_t id, size_t capacity)
{
    uint32_t hash = id * 2654435769u;
    return (size_t)(((uint64_t)hash * capacity) >> 32);
}

static foam_entry *find(foam_entry *table, size_t capacity, uint32_t id)
{
    if (!table)
        return NULL;
    for (size_t i = slot_of(id, capacity);; i = (i + 1) & (capacity - 1)) {
        if (!table[i].used)
            return NULL;
        if (table[i].id == id)
            return &table[i];
    }
}

/* The entry of `id` in `table`, made empty-handed when new; *fresh tells which. */
static foam_entry *insert(foam_entry *table, size_t capacity, uint32_t id, bool *fresh)
{
    size_t i = slot_of(id, capacity);
    while (table[i].used && table[i].id != id)
        i = (i + 1) & (capacity - 1);
    *fresh = !table[i].used;
    table[i].used = 1;
    table[i].id = id;
    return &table[i];
}

static fc_code out_of_memory(fc_error *err)
{
    return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the foam state");
}

/* Tables of at least LOAD_FACTOR_INVERSE * count slots, keeping the last frame's entries. */
static fc_code reserve_tables(fc_foam_state *s, uint64_t count, fc_error *err)
{
    size_t needed = 16;
    while (needed < count * LOAD_FACTOR_INVERSE)
        needed *= 2;
    if (needed <= s->capacity)
        return FC_OK;
    foam_entry *last = calloc(needed, sizeof *last);
    foam_entry *scratch = last ? malloc(needed * sizeof *scratch) : NULL;
    if (!scratch) {
        free(last);
        return out_of_memory(err);
    }
    const foam_entry *old = s->tables[s->current];
    for (size_t i = 0; old && i < s->capacity; i++) {
        bool fresh;
        if (old[i].used)
            *insert(last, needed, old[i].id, &fresh) = old[i];
    }
    free(s->tables[0]);
    free(s->tables[1]);
    s->tables[0] = last;
    s->tables[1] = scratch;
    s->current = 0;
    s->capacity = needed;
    return FC_OK;
}

static fc_code reserve_amplitudes(fc_foam_state *s, uint64_t count, fc_error *err)
{
    if (count <= s->amplitude_capacity)
        return FC_OK;
    float *grown = realloc(s->amplitude, count * sizeof *grown);
    if (!grown)
        return out_of_memory(err);
    s->amplitude = grown;
    s->amplitude_capacity = count;
    return FC_OK;
}

static float velocity_change(const float a[3], const float b[3])
{
    float d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* The raise of a particle this frame: its last raise cooled by one frame,
 * back to turbulent when its velocity jumped (eq. 12). */
static float next_raise(const foam_entry *last, const float velocity[3], const fc_settings *settings)
{
    if (!last)
        return 0.0f;
    float decay = fminf(fmaxf(settings->foam_decay, 0.0f), 1.0f);
    float raise = last->raise * decay;
    if (velocity_change(velocity, last->velocity) > settings->foam_tau)
        raise = fmaxf(raise, TURBULENT_RAISE);
    return raise;
}

static void advance_tables(fc_foam_state *s, const fc_frame *frame, const fc_settings *settings)
{
    foam_entry *last = s->tables[s->current], *next = s->tables[1 - s->current];
    memset(next, 0, s->capacity * sizeof *next);
    for (uint64_t i = 0; i < frame->count; i++) {
        const float *v = frame->velocity + 3 * (size_t)i;
        bool fresh;
        foam_entry *e = insert(next, s->capacity, frame->ids[i], &fresh);
        /* A repeated id within one frame keeps its first particle's state. */
        if (fresh) {
            e->raise = next_raise(find(last, s->capacity, frame->ids[i]), v, settings);
            memcpy(e->velocity, v, sizeof e->velocity);
        }
        s->amplitude[i] = 1.0f + e->raise;
    }
    s->current = 1 - s->current;
}

/* Without ids nothing persists across frames, without velocities nothing can
 * jump: every particle gets the calm amplitude and the history is dropped. */
static void reset(fc_foam_state *s, uint64_t count)
{
    if (s->tables[s->current])
        memset(s->tables[s->current], 0, s->capacity * sizeof(foam_entry));
    for (uint64_t i = 0; i < count; i++)
        s->amplitude[i] = 1.0f;
}

fc_code fc_foam_state_advance(fc_foam_state *s, fc_pipeline *p, const fc_frame *frame,
                              const fc_settings *settings, fc_error *err)
{
    if (!s || !p || !frame || !settings)
        return fc_error_set(err, FC_ERR_USAGE, "fc_foam_state_advance: missing state, pipeline, frame or settings");
    fc_particle_attributes *attributes = fc_pipeline_particle_attributes(p);
    if (frame->count != attributes->count)
        return fc_error_set(err, FC_ERR_USAGE, "fc_foam_state_advance: frame of %llu particles, %llu uploaded",
                            (unsigned long long)frame->count, (unsigned long long)attributes->count);
    fc_code code = reserve_amplitudes(s, frame->count, err);
    bool tracked = frame->ids && frame->velocity;
    if (code == FC_OK && tracked)
        code = reserve_tables(s, frame->count, err);
    if (code != FC_OK)
        return code;
    if (tracked)
        advance_tables(s, frame, settings);
    else
        reset(s, frame->count);
    return fc_particle_attributes_set_amplitudes(attributes, s->amplitude, err);
}

const float *fc_foam_state_amplitudes(const fc_foam_state *s)
{
    return s ? s->amplitude : NULL;
}

fc_code fc_pipeline_set_amplitudes(fc_pipeline *p, const float *amplitude, uint64_t count, fc_error *err)
{
    if (!p || (!amplitude && count > 0))
        return fc_error_set(err, FC_ERR_USAGE, "fc_pipeline_set_amplitudes: missing pipeline or amplitudes");
    fc_particle_attributes *attributes = fc_pipeline_particle_attributes(p);
    if (count != attributes->count)
        return fc_error_set(err, FC_ERR_USAGE, "fc_pipeline_set_amplitudes: %llu amplitudes, %llu particles uploaded",
                            (unsigned long long)count, (unsigned long long)attributes->count);
    return fc_particle_attributes_set_amplitudes(attributes, amplitude, err);
}

float fc_foam_state_amplitude(const fc_foam_state *s, uint32_t id)
{
    const foam_entry *e = find(s->tables[s->current], s->capacity, id);
    return e ? 1.0f + e->raise : 1.0f;
}
