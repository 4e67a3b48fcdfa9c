/* fc_parallel.c — see fc_parallel.h. */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include "fc_parallel.h"

#include <pthread.h>
#include <sched.h>
#include <stdbool.h>
#include <unistd.h>

typedef struct range_task {
    fc_range_work work;
    void *context;
    unsigned worker;
    uint64_t begin, end;
} range_task;

unsigned fc_usable_cores(void)
{
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        return (unsigned)CPU_COUNT(&set);
    long online = sysconf(_SC_NPROCESSORS_ONLN);
    return online > 0 ? (unsigned)(online < 4096 ? online : 4096) : 1u;
}

unsigned fc_parallel_workers(uint64_t count)
{
    uint64_t worth = count / FC_PARALLEL_MIN_ITEMS_PER_WORKER;
    unsigned workers = fc_usable_cores();
    workers = workers < FC_PARALLEL_MAX_WORKERS ? workers : FC_PARALLEL_MAX_WORKERS;
    workers = worth < workers ? (unsigned)worth : workers;
    return workers > 0 ? workers : 1u;
}

static void *run_task(void *arg)
{
    const range_task *t = arg;
    t->work(t->context, t->worker, t->begin, t->end);
    return NULL;
}

void fc_parallel_for(uint64_t count, unsigned workers, fc_range_work work, void *context)
{
    range_task tasks[FC_PARALLEL_MAX_WORKERS];
    pthread_t threads[FC_PARALLEL_MAX_WORKERS];
    bool started[FC_PARALLEL_MAX_WORKERS] = {false};
    workers = workers < 1 ? 1 : workers > FC_PARALLEL_MAX_WORKERS ? FC_PARALLEL_MAX_WORKERS : workers;
    uint64_t share = count / workers, extra = count % workers, begin = 0;
    for (unsigned k = 0; k < workers; k++) {
        /* The first `extra` ranges hold one item more. */
        uint64_t end = begin + share + (k < extra);
        tasks[k] = (range_task){work, context, k, begin, end};
        begin = end;
    }
    for (unsigned k = 1; k < workers; k++)
        started[k] = pthread_create(&threads[k], NULL, run_task, &tasks[k]) == 0;
    run_task(&tasks[0]);
    for (unsigned k = 1; k < workers; k++) {
        if (started[k])
            pthread_join(threads[k], NULL);
        else
            run_task(&tasks[k]);
    }
}
