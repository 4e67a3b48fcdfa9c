/* frame_pool.c — see frame_pool.h. */
#include "uploads/frame_pool.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

typedef struct waiting_block {
    uint8_t *bytes;
    size_t size;
} waiting_block;

struct fc_frame_pool {
    pthread_mutex_t lock;
    size_t max_blocks;
    size_t max_bytes;
    waiting_block *waiting;   /* max_blocks slots, oldest first */
    size_t count;
    size_t bytes;
    uint64_t allocations;
};

fc_code fc_frame_pool_create(size_t max_blocks, size_t max_bytes, fc_frame_pool **out, fc_error *err)
{
    fc_frame_pool *pool = calloc(1, sizeof *pool);
    if (pool && max_blocks > 0)
        pool->waiting = calloc(max_blocks, sizeof *pool->waiting);
    if (!pool || (max_blocks > 0 && !pool->waiting) || pthread_mutex_init(&pool->lock, NULL) != 0) {
        if (pool)
            free(pool->waiting);
        free(pool);
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the frame pool");
    }
    pool->max_blocks = max_blocks;
    pool->max_bytes = max_bytes;
    *out = pool;
    return FC_OK;
}

void fc_frame_pool_destroy(fc_frame_pool *pool)
{
    if (!pool)
        return;
    for (size_t i = 0; i < pool->count; i++)
        free(pool->waiting[i].bytes);
    free(pool->waiting);
    pthread_mutex_destroy(&pool->lock);
    free(pool);
}

/* Removes slot i, keeping the others in age order. Lock held. */
static uint8_t *remove_waiting(fc_frame_pool *pool, size_t i)
{
    uint8_t *bytes = pool->waiting[i].bytes;
    pool->bytes -= pool->waiting[i].size;
    memmove(&pool->waiting[i], &pool->waiting[i + 1], (pool->count - i - 1) * sizeof *pool->waiting);
    pool->count--;
    return bytes;
}

/* The waiting block of lo..hi bytes that fits tightest (the newest of equals:
 * its pages are the likeliest to be warm), taken out; NULL when none. */
static uint8_t *reuse_between(fc_frame_pool *pool, size_t lo, size_t hi, size_t *size)
{
    pthread_mutex_lock(&pool->lock);
    size_t best = pool->count;
    for (size_t i = pool->count; i-- > 0;)
        if (pool->waiting[i].size >= lo && pool->waiting[i].size <= hi &&
            (best == pool->count || pool->waiting[i].size < pool->waiting[best].size))
            best = i;
    uint8_t *bytes = NULL;
    if (best < pool->count) {
        *size = pool->waiting[best].size;
        bytes = remove_waiting(pool, best);
    }
    pthread_mutex_unlock(&pool->lock);
    return bytes;
}

uint8_t *fc_frame_pool_reuse(fc_frame_pool *pool, size_t size)
{
    size_t got;
    return reuse_between(pool, size, size, &got);
}

uint8_t *fc_frame_pool_reuse_roomy(fc_frame_pool *pool, size_t size, size_t *got)
{
    size_t slack = size / 8;
    return reuse_between(pool, size, size <= SIZE_MAX - slack ? size + slack : SIZE_MAX, got);
}

uint8_t *fc_frame_pool_take(fc_frame_pool *pool, size_t size)
{
    uint8_t *bytes = fc_frame_pool_reuse(pool, size);
    if (bytes)
        return bytes;
    bytes = malloc(size ? size : 1);
    if (bytes && size >= FC_FRAME_POOL_MIN_BYTES)
        fc_frame_pool_note_allocation(pool);
    return bytes;
}

void fc_frame_pool_give(fc_frame_pool *pool, uint8_t *block, size_t size)
{
    if (!block)
        return;
    if (size < FC_FRAME_POOL_MIN_BYTES || size > pool->max_bytes || pool->max_blocks == 0) {
        free(block);
        return;
    }
    pthread_mutex_lock(&pool->lock);
    /* The oldest make room: a stream that changed its frame size leaves its old blocks behind. */
    while (pool->count == pool->max_blocks || pool->bytes + size > pool->max_bytes)
        free(remove_waiting(pool, 0));
    pool->waiting[pool->count++] = (waiting_block){block, size};
    pool->bytes += size;
    pthread_mutex_unlock(&pool->lock);
}

static uint8_t *take_from_pool(void *pool, size_t size)
{
    return fc_frame_pool_take(pool, size);
}

static void give_to_pool(void *pool, uint8_t *block, size_t size)
{
    fc_frame_pool_give(pool, block, size);
}

fc_block_source fc_frame_pool_source(fc_frame_pool *pool)
{
    return (fc_block_source){take_from_pool, give_to_pool, pool};
}

void fc_frame_pool_give_view(fc_frame_pool *pool, fc_frame_view *view)
{
    fc_frame_pool_give(pool, view->block, view->block_size);
    memset(view, 0, sizeof *view);
}

uint64_t fc_frame_pool_allocations(fc_frame_pool *pool)
{
    pthread_mutex_lock(&pool->lock);
    uint64_t allocations = pool->allocations;
    pthread_mutex_unlock(&pool->lock);
    return allocations;
}

void fc_frame_pool_note_allocation(fc_frame_pool *pool)
{
    pthread_mutex_lock(&pool->lock);
    pool->allocations++;
    pthread_mutex_unlock(&pool->lock);
}
