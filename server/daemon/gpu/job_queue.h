/* job_queue.h — a FIFO of render jobs between threads: producers push, a
 * consumer blocks in pop until a job arrives or the queue is closed. A queue
 * with a wake fd (an eventfd) also makes that fd readable on every push, so a
 * poll() loop can wait for it. */
#ifndef FC_DAEMON_JOB_QUEUE_H
#define FC_DAEMON_JOB_QUEUE_H

#include <pthread.h>
#include <stdbool.h>

#include "gpu/render_job.h"

typedef struct fc_job_queue {
    pthread_mutex_t lock;
    pthread_cond_t ready;
    fc_render_job *head;
    fc_render_job *tail;
    bool closed;
    int wake_fd;          /* eventfd written on each push; -1 for none */
} fc_job_queue;

fc_code fc_job_queue_init(fc_job_queue *q, int wake_fd, fc_error *err);
/* Frees the jobs still queued. No thread may use the queue any more. */
void fc_job_queue_destroy(fc_job_queue *q);

/* Appends the job (a closed queue frees it instead). */
void fc_job_queue_push(fc_job_queue *q, fc_render_job *job);
/* The oldest job, waiting for one; NULL once the queue is closed and empty. */
fc_render_job *fc_job_queue_pop(fc_job_queue *q);
/* Every queued job as a list, oldest first, without waiting (NULL when empty). */
fc_render_job *fc_job_queue_take_all(fc_job_queue *q);
/* Wakes every waiting pop; later pushes free their jobs. */
void fc_job_queue_close(fc_job_queue *q);

#endif
