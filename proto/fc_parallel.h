/* fc_parallel.h — a loop over [0, count) cut into contiguous ranges, run on
 * the calling thread and on helper threads started for the call: for the
 * passes over every particle of a large frame whose iterations are
 * independent (the radius estimate's scan, the spray classes' counts).
 * Every range's result depends only on its items, and callers merge the
 * workers' results in an order-free way (sums of integers, minima), so the
 * outcome never depends on how many workers ran. */
#ifndef FC_PARALLEL_H
#define FC_PARALLEL_H

#include <stdint.h>

/* Workers at most, whatever the machine. */
#define FC_PARALLEL_MAX_WORKERS 16u
/* Items a worker is worth starting for: below it, a thread costs more than it saves. */
#define FC_PARALLEL_MIN_ITEMS_PER_WORKER 65536u

/* Range `worker` of `workers`: items [begin, end). */
typedef void (*fc_range_work)(void *context, unsigned worker, uint64_t begin, uint64_t end);

/* The cores this process may run on: under Slurm, a container or taskset
 * that is the affinity mask, fewer than the machine's online cores; >= 1. */
unsigned fc_usable_cores(void);

/* How many workers a loop over `count` items uses: the usable cores, at most
 * FC_PARALLEL_MAX_WORKERS and one per FC_PARALLEL_MIN_ITEMS_PER_WORKER
 * items; at least 1. Callers size per-worker state with it. */
unsigned fc_parallel_workers(uint64_t count);

/* Calls work(context, k, begin_k, end_k) for k in [0, workers), the ranges
 * cutting [0, count) into nearly equal contiguous pieces in order: range 0
 * on the calling thread, the others on helper threads (a helper that cannot
 * start has its range run on the calling thread). Returns when all are done. */
void fc_parallel_for(uint64_t count, unsigned workers, fc_range_work work, void *context);

#endif
