/* test_frame_pool.c — the daemon's frame block pool: a block given back is
 * handed out again for the same size and never for another, payload-sized
 * requests take the tightest block within an eighth, what waits stays within
 * its bounds (oldest out first), small blocks are not pooled, allocations are
 * counted, and blocks given back from another thread are reused. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "test_util.h"
#include "uploads/frame_pool.h"

enum { MIB = 1 << 20 };

static fc_frame_pool *new_pool(size_t blocks, size_t bytes)
{
    fc_frame_pool *pool = NULL;
    fc_error err;
    CHECK_CODE(fc_frame_pool_create(blocks, bytes, &pool, &err), FC_OK);
    return pool;
}

static void same_size_is_reused_other_sizes_are_not(void)
{
    fc_frame_pool *pool = new_pool(4, 64 * MIB);
    uint8_t *a = fc_frame_pool_take(pool, 3 * MIB);
    CHECK(a != NULL);
    CHECK(fc_frame_pool_allocations(pool) == 1);
    memset(a, 0x5a, 3 * MIB);
    fc_frame_pool_give(pool, a, 3 * MIB);
    CHECK_MSG(fc_frame_pool_reuse(pool, 3 * MIB - 4) == NULL, "a smaller request got the 3 MiB block");
    CHECK_MSG(fc_frame_pool_reuse(pool, 3 * MIB + 4) == NULL, "a larger request got the 3 MiB block");
    uint8_t *again = fc_frame_pool_take(pool, 3 * MIB);
    CHECK_MSG(again == a, "the block given back was not handed out again");
    CHECK(fc_frame_pool_allocations(pool) == 1);
    CHECK_MSG(again && again[0] == 0x5a && again[3 * MIB - 1] == 0x5a, "a reused block is the same memory");
    uint8_t *other = fc_frame_pool_take(pool, 2 * MIB);
    CHECK(other != NULL && other != a);
    CHECK(fc_frame_pool_allocations(pool) == 2);
    fc_frame_pool_give(pool, again, 3 * MIB);
    fc_frame_pool_give(pool, other, 2 * MIB);
    CHECK(fc_frame_pool_reuse(pool, 2 * MIB) == other);
    CHECK(fc_frame_pool_reuse(pool, 3 * MIB) == a);
    CHECK(fc_frame_pool_reuse(pool, 3 * MIB) == NULL);
    free(a);
    free(other);
    fc_frame_pool_destroy(pool);
}

static void payloads_take_the_tightest_block_within_an_eighth(void)
{
    fc_frame_pool *pool = new_pool(4, 64 * MIB);
    uint8_t *big = malloc(9 * MIB), *tight = malloc(8 * MIB + 4096);
    fc_frame_pool_give(pool, big, 9 * MIB);
    fc_frame_pool_give(pool, tight, 8 * MIB + 4096);
    size_t got = 0;
    CHECK(fc_frame_pool_reuse_roomy(pool, 8 * MIB, &got) == tight);
    CHECK(got == 8 * MIB + 4096);
    /* 9 MiB is more than an eighth above 7 MiB... */
    CHECK(fc_frame_pool_reuse_roomy(pool, 7 * MIB, &got) == NULL);
    /* ...but within an eighth of 8 MiB. */
    CHECK(fc_frame_pool_reuse_roomy(pool, 8 * MIB, &got) == big);
    CHECK(got == 9 * MIB);
    free(big);
    free(tight);
    fc_frame_pool_destroy(pool);
}

static void what_waits_is_bounded_oldest_out_first(void)
{
    fc_frame_pool *pool = new_pool(2, 10 * MIB);
    uint8_t *first = malloc(1 * MIB), *second = malloc(2 * MIB), *third = malloc(3 * MIB);
    fc_frame_pool_give(pool, first, 1 * MIB);
    fc_frame_pool_give(pool, second, 2 * MIB);
    fc_frame_pool_give(pool, third, 3 * MIB);   /* two blocks at most: the first goes */
    CHECK(fc_frame_pool_reuse(pool, 1 * MIB) == NULL);
    uint8_t *second_again = fc_frame_pool_reuse(pool, 2 * MIB);
    CHECK(second_again == second);
    fc_frame_pool_give(pool, second_again, 2 * MIB);
    uint8_t *large = malloc(8 * MIB);
    fc_frame_pool_give(pool, large, 8 * MIB);   /* 10 MiB at most: 3 + 2 + 8 do not fit, the oldest goes */
    CHECK(fc_frame_pool_reuse(pool, 3 * MIB) == NULL);
    CHECK(fc_frame_pool_reuse(pool, 2 * MIB) == second);
    free(second);
    CHECK(fc_frame_pool_reuse(pool, 8 * MIB) == large);
    fc_frame_pool_give(pool, large, 8 * MIB);
    uint8_t *huge = malloc(11 * MIB);
    fc_frame_pool_give(pool, huge, 11 * MIB);   /* beyond max_bytes: freed at once, the 8 MiB block stays */
    CHECK(fc_frame_pool_reuse(pool, 11 * MIB) == NULL);
    uint8_t *small = malloc(FC_FRAME_POOL_MIN_BYTES - 1);
    fc_frame_pool_give(pool, small, FC_FRAME_POOL_MIN_BYTES - 1);
    CHECK(fc_frame_pool_reuse(pool, FC_FRAME_POOL_MIN_BYTES - 1) == NULL);
    CHECK(fc_frame_pool_reuse(pool, 8 * MIB) == large);
    free(large);
    /* Small blocks are plain malloc, not counted. */
    uint8_t *tiny = fc_frame_pool_take(pool, 100);
    CHECK(tiny != NULL && fc_frame_pool_allocations(pool) == 0);
    fc_frame_pool_give(pool, tiny, 100);
    fc_frame_pool_destroy(pool);
}

typedef struct give_back {
    fc_frame_pool *pool;
    uint8_t *block;
} give_back;

static void *give_from_thread(void *arg)
{
    give_back *g = arg;
    fc_frame_pool_give(g->pool, g->block, 4 * MIB);
    return NULL;
}

/* A stream's cycle: take, hand to another thread (the GL thread), which gives it back. */
static void blocks_given_back_by_another_thread_are_reused(void)
{
    fc_frame_pool *pool = new_pool(8, 64 * MIB);
    for (int frame = 0; frame < 50; frame++) {
        give_back g = {pool, fc_frame_pool_take(pool, 4 * MIB)};
        CHECK(g.block != NULL);
        pthread_t thread;
        CHECK(pthread_create(&thread, NULL, give_from_thread, &g) == 0);
        pthread_join(thread, NULL);
    }
    CHECK_MSG(fc_frame_pool_allocations(pool) == 1, "%llu allocations for 50 frames",
              (unsigned long long)fc_frame_pool_allocations(pool));
    fc_frame_pool_destroy(pool);
}

static void as_a_block_source(void)
{
    fc_frame_pool *pool = new_pool(4, 64 * MIB);
    fc_block_source src = fc_frame_pool_source(pool);
    uint8_t *block = src.take(src.ctx, 1 * MIB);
    CHECK(block != NULL && fc_frame_pool_allocations(pool) == 1);
    src.give(src.ctx, block, 1 * MIB);
    fc_frame_view view = {.block = src.take(src.ctx, 1 * MIB), .block_size = 1 * MIB};
    CHECK(view.block == block && fc_frame_pool_allocations(pool) == 1);
    fc_frame_pool_give_view(pool, &view);
    CHECK(view.block == NULL && view.block_size == 0);
    CHECK(fc_frame_pool_reuse(pool, 1 * MIB) == block);
    free(block);
    fc_frame_pool_destroy(pool);
}

int main(void)
{
    same_size_is_reused_other_sizes_are_not();
    payloads_take_the_tightest_block_within_an_eighth();
    what_waits_is_bounded_oldest_out_first();
    blocks_given_back_by_another_thread_are_reused();
    as_a_block_source();
    return test_result();
}
