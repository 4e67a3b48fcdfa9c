/* density_order.h — the draw order of a frame's particles, densest first: for
 * any density threshold the surface particles (density >= threshold) are then
 * a prefix of the order and the spray the rest, so one upload serves every
 * threshold a render may ask for. */
#ifndef FC_DENSITY_ORDER_H
#define FC_DENSITY_ORDER_H

#include <stdint.h>

#include "fluidcast_types.h"

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

void fc_density_order_free(fc_density_order *o);

#endif
