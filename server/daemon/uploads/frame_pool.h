/* frame_pool.h — recycles the big blocks frames live in (received payloads,
 * decoded particles), so a producer streaming same-sized frames reuses warm
 * memory instead of faulting in fresh pages for every frame.
 *
 * A block is plain malloc() memory of a known size; a block given back waits
 * in the pool for a request of exactly that size. What waits is bounded (at
 * most max_blocks blocks and max_bytes bytes together, the oldest freed first)
 * and belongs to no connection: it is daemon memory, not counted against any
 * --max-session-memory. Thread-safe: the GL thread gives back the blocks of
 * the frames it drops. */
#ifndef FC_DAEMON_FRAME_POOL_H
#define FC_DAEMON_FRAME_POOL_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "wire.h"

/* Blocks below this are not pooled: malloc serves them cheaply from its heap. */
#define FC_FRAME_POOL_MIN_BYTES (64u << 10)

typedef struct fc_frame_pool fc_frame_pool;

fc_code fc_frame_pool_create(size_t max_blocks, size_t max_bytes, fc_frame_pool **out, fc_error *err);
/* Frees the waiting blocks and the pool. NULL is ignored. */
void fc_frame_pool_destroy(fc_frame_pool *pool);

/* A waiting block of exactly `size` bytes, or NULL when none waits (nothing is allocated). */
uint8_t *fc_frame_pool_reuse(fc_frame_pool *pool, size_t size);
/* A waiting block of size .. size + size/8 bytes (the smallest), its size in
 * *got; NULL when none waits. For payloads, whose sizes vary a little from
 * frame to frame when they are compressed. */
uint8_t *fc_frame_pool_reuse_roomy(fc_frame_pool *pool, size_t size, size_t *got);
/* A waiting block of `size` bytes, else a newly allocated one (counted when
 * poolable); NULL when memory runs out. */
uint8_t *fc_frame_pool_take(fc_frame_pool *pool, size_t size);
/* Hands a block back to wait for its next use; frees it when it is too small
 * to pool or larger than max_bytes. NULL is ignored. */
void fc_frame_pool_give(fc_frame_pool *pool, uint8_t *block, size_t size);

/* The pool as a decoder's block source (fc_wire_view_frame_packed, fc_wire_view_chunk). */
fc_block_source fc_frame_pool_source(fc_frame_pool *pool);
/* Gives a view's block back (nothing when it has none) and empties the view. */
void fc_frame_pool_give_view(fc_frame_pool *pool, fc_frame_view *view);

/* Blocks fc_frame_pool_take allocated so far (plus those reported with
 * fc_frame_pool_note_allocation): stays flat in a steady stream. */
uint64_t fc_frame_pool_allocations(fc_frame_pool *pool);
/* Counts a block that its user allocated itself before giving it to the pool. */
void fc_frame_pool_note_allocation(fc_frame_pool *pool);

#endif
