/* density_order.c — stable descending sort of particle densities (LSD radix). */
#include "density_order.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

/* Three passes of 11, 11 and 10 bits cover a 32-bit key. */
#define RADIX_BITS 11
#define RADIX_BUCKETS (1u << RADIX_BITS)
#define RADIX_PASSES 3

/* An unsigned key whose ascending order is the descending order of the
 * float: IEEE floats compare like sign-magnitude integers, so flipping every
 * bit of negatives and only the sign bit of positives makes them compare as
 * unsigned integers, and the final complement reverses the order. */
static uint32_t descending_key(float value)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    uint32_t ascending = bits & 0x80000000u ? ~bits : bits | 0x80000000u;
    return ~ascending;
}

static fc_code reserve(fc_density_order *o, uint64_t count, fc_error *err)
{
    if (count <= o->capacity)
        return FC_OK;
    uint32_t **arrays[] = {&o->order, &o->keys, &o->key_scratch, &o->index_scratch};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) {
        uint32_t *grown = realloc(*arrays[i], count * sizeof(uint32_t));
        if (!grown)
            return fc_error_set(err, FC_ERR_NOMEM, "out of memory ordering %llu particles by density",
                                (unsigned long long)count);
        *arrays[i] = grown;
    }
    o->capacity = count;
    return FC_OK;
}

/* How many keys hold each value of each pass's digit, counted in one read of the keys. */
static void count_digits(const uint32_t *keys, uint64_t count, uint64_t (*start)[RADIX_BUCKETS])
{
    memset(start, 0, RADIX_PASSES * sizeof *start);
    for (uint64_t i = 0; i < count; i++)
        for (unsigned pass = 0; pass < RADIX_PASSES; pass++)
            start[pass][(keys[i] >> (pass * RADIX_BITS)) & (RADIX_BUCKETS - 1)]++;
}

/* Turns a digit's counts into the first slot of each value; false when one
 * value holds every key (the pass would move nothing). */
static bool digit_starts(uint64_t *start, uint64_t count)
{
    uint64_t sum = 0;
    bool moves = true;
    for (uint32_t b = 0; b < RADIX_BUCKETS; b++) {
        uint64_t n = start[b];
        moves = moves && n != count;
        start[b] = sum;
        sum += n;
    }
    return moves;
}

/* One counting-sort pass on the digit at `shift`, from (keys, index) into (keys_out, index_out). */
static void radix_pass(const uint32_t *keys, const uint32_t *index, uint32_t *keys_out, uint32_t *index_out,
                       uint64_t count, unsigned shift, uint64_t *start)
{
    for (uint64_t i = 0; i < count; i++) {
        uint64_t slot = start[(keys[i] >> shift) & (RADIX_BUCKETS - 1)]++;
        keys_out[slot] = keys[i];
        index_out[slot] = index[i];
    }
}

fc_code fc_density_order_sort(fc_density_order *o, const float *density, uint64_t count, fc_error *err)
{
    if (count > (uint64_t)INT32_MAX)
        return fc_error_set(err, FC_ERR_LIMIT, "%llu particles exceed the %d one draw call can render",
                            (unsigned long long)count, INT32_MAX);
    fc_code code = reserve(o, count, err);
    if (code != FC_OK)
        return code;
    for (uint64_t i = 0; i < count; i++) {
        o->keys[i] = descending_key(density[i]);
        o->index_scratch[i] = (uint32_t)i;
    }
    uint64_t start[RADIX_PASSES][RADIX_BUCKETS];
    count_digits(o->keys, count, start);
    /* Ping-pong between the two buffer pairs, skipping the passes whose digit
     * is the same in every key (all but one without densities, where the
     * keys are the spray's and the rest's): the result belongs in
     * (key_scratch, order), where the sorted keys stay for
     * fc_density_order_count_at_least. */
    uint32_t *keys_in = o->keys, *index_in = o->index_scratch;
    uint32_t *keys_out = o->key_scratch, *index_out = o->order;
    for (unsigned pass = 0; pass < RADIX_PASSES; pass++) {
        if (!digit_starts(start[pass], count))
            continue;
        radix_pass(keys_in, index_in, keys_out, index_out, count, pass * RADIX_BITS, start[pass]);
        uint32_t *k = keys_in, *x = index_in;
        keys_in = keys_out;
        index_in = index_out;
        keys_out = k;
        index_out = x;
    }
    if (keys_in != o->key_scratch && count > 0) {
        memcpy(o->key_scratch, keys_in, count * sizeof *keys_in);
        memcpy(o->order, index_in, count * sizeof *index_in);
    }
    return FC_OK;
}

uint64_t fc_density_order_count_at_least(const fc_density_order *o, uint64_t count, float threshold)
{
    /* density >= threshold exactly when its key is <= the threshold's. */
    uint32_t limit = descending_key(threshold);
    uint64_t lo = 0, hi = count;
    while (lo < hi) {
        uint64_t mid = lo + (hi - lo) / 2;
        if (o->key_scratch[mid] <= limit)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

void fc_density_order_free(fc_density_order *o)
{
    free(o->order);
    free(o->keys);
    free(o->key_scratch);
    free(o->index_scratch);
    *o = (fc_density_order){0};
}
