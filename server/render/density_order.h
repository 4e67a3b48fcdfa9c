/* density_order.h — the draw order of a frame's particles, densest first: for
 * any density threshold the surface particles (density >= threshold) are then
 * a prefix of the order and the spray the rest, so one upload serves every
 * threshold a render may ask for. */
#ifndef FC_DENSITY_ORDER_H
#define FC_DENSITY_ORDER_H

#include <stdint.h>

#include "fluidcast_types.h"

/* Gathers in this order read the frame at random: fetching the particle this
 * many slots ahead overlaps the cache misses instead of waiting on each
 * (1M-particle frames gather about twice as fast). */
#define FC_DRAW_ORDER_PREFETCH 16

typedef struct fc_density_order {
    uint32_t *order;           /* draw slot -> frame index, `count` entries */
    uint32_t *keys;            /* scratch of the sort, reused across frames */
    uint32_t *key_scratch;
    uint32_t *index_scratch;
    uint64_t capacity;         /* entries each array holds; they only grow */
} fc_density_order;

/* Sorts `count` densities (finite) into o->order, descending and stable
 * (equal densities keep their frame order), with a radix sort: O(count), no
 * allocation once the arrays are large enough. FC_ERR_NOMEM when they cannot
 * grow; FC_ERR_LIMIT beyond 2^31 - 1 particles (the most one draw call takes). */
fc_code fc_density_order_sort(fc_density_order *o, const float *density, uint64_t count, fc_error *err);

/* How many of the `count` particles the last sort ordered have a density >=
 * threshold: the length of the order's prefix they fill, found in the sort's
 * keys, so the densities need no copy in draw order. */
uint64_t fc_density_order_count_at_least(const fc_density_order *o, uint64_t count, float threshold);

void fc_density_order_free(fc_density_order *o);

#endif
