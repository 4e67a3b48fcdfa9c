/* spacemouse_queue.c — a mutex-protected ring of fc_sm_event. */
#include "spacemouse_events.h"

#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <time.h>

#include "fc_error.h"

struct fc_sm_queue {
    pthread_mutex_t lock;
    pthread_cond_t nonempty;      /* uses CLOCK_MONOTONIC for timed waits */
    fc_sm_event *ring;
    size_t capacity, head, count;
    uint32_t dropped;             /* lost since the last pop */
};

fc_code fc_sm_queue_create(size_t capacity, fc_sm_queue **out, fc_error *err)
{
    *out = NULL;
    if (capacity < 1)
        return fc_error_set(err, FC_ERR_USAGE, "event queue capacity must be at least 1");
    fc_sm_queue *q = calloc(1, sizeof *q);
    if (q)
        q->ring = calloc(capacity, sizeof *q->ring);
    if (!q || !q->ring) {
        free(q);
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for %zu SpaceMouse events", capacity);
    }
    q->capacity = capacity;
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    pthread_cond_init(&q->nonempty, &attr);
    pthread_condattr_destroy(&attr);
    pthread_mutex_init(&q->lock, NULL);
    *out = q;
    return FC_OK;
}

void fc_sm_queue_destroy(fc_sm_queue *q)
{
    if (!q)
        return;
    pthread_mutex_destroy(&q->lock);
    pthread_cond_destroy(&q->nonempty);
    free(q->ring);
    free(q);
}

void fc_sm_queue_push(fc_sm_queue *q, const fc_sm_event *event)
{
    pthread_mutex_lock(&q->lock);
    if (q->count == q->capacity) {
        q->head = (q->head + 1) % q->capacity;
        q->count--;
        q->dropped++;
    }
    q->ring[(q->head + q->count) % q->capacity] = *event;
    q->count++;
    pthread_cond_signal(&q->nonempty);
    pthread_mutex_unlock(&q->lock);
}

static struct timespec deadline_after(int timeout_ms)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    t.tv_sec += timeout_ms / 1000;
    t.tv_nsec += (long)(timeout_ms % 1000) * 1000000L;
    if (t.tv_nsec >= 1000000000L) {
        t.tv_sec++;
        t.tv_nsec -= 1000000000L;
    }
    return t;
}

bool fc_sm_queue_pop(fc_sm_queue *q, fc_sm_event *event, int timeout_ms)
{
    struct timespec deadline = deadline_after(timeout_ms > 0 ? timeout_ms : 0);
    pthread_mutex_lock(&q->lock);
    while (q->count == 0 && timeout_ms != 0) {
        int rc = timeout_ms < 0 ? pthread_cond_wait(&q->nonempty, &q->lock)
                                : pthread_cond_timedwait(&q->nonempty, &q->lock, &deadline);
        if (rc == ETIMEDOUT)
            break;
    }
    bool got = q->count > 0;
    if (got) {
        *event = q->ring[q->head];
        event->dropped = q->dropped;
        q->dropped = 0;
        q->head = (q->head + 1) % q->capacity;
        q->count--;
    }
    pthread_mutex_unlock(&q->lock);
    return got;
}
