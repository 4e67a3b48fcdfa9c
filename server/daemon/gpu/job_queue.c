/* job_queue.c — see job_queue.h. */
#include "gpu/job_queue.h"

#include <string.h>
#include <unistd.h>

#include "fc_error.h"

fc_code fc_job_queue_init(fc_job_queue *q, int wake_fd, fc_error *err)
{
    memset(q, 0, sizeof *q);
    q->wake_fd = wake_fd;
    if (pthread_mutex_init(&q->lock, NULL) != 0)
        return fc_error_set(err, FC_ERR_INTERNAL, "cannot create a queue mutex");
    if (pthread_cond_init(&q->ready, NULL) != 0) {
        pthread_mutex_destroy(&q->lock);
        return fc_error_set(err, FC_ERR_INTERNAL, "cannot create a queue condition");
    }
    return FC_OK;
}

void fc_job_queue_destroy(fc_job_queue *q)
{
    fc_render_job_free_list(q->head);
    q->head = q->tail = NULL;
    pthread_cond_destroy(&q->ready);
    pthread_mutex_destroy(&q->lock);
}

void fc_job_queue_push(fc_job_queue *q, fc_render_job *job)
{
    job->next = NULL;
    pthread_mutex_lock(&q->lock);
    bool closed = q->closed;
    if (!closed) {
        if (q->tail)
            q->tail->next = job;
        else
            q->head = job;
        q->tail = job;
        pthread_cond_signal(&q->ready);
    }
    pthread_mutex_unlock(&q->lock);
    if (closed) {
        fc_render_job_free(job);
        return;
    }
    if (q->wake_fd >= 0) {
        uint64_t one = 1;
        /* Only fails when the counter would overflow, i.e. the reader is already due to wake. */
        ssize_t written = write(q->wake_fd, &one, sizeof one);
        (void)written;
    }
}

fc_render_job *fc_job_queue_pop(fc_job_queue *q)
{
    pthread_mutex_lock(&q->lock);
    while (!q->head && !q->closed)
        pthread_cond_wait(&q->ready, &q->lock);
    fc_render_job *job = q->head;
    if (job) {
        q->head = job->next;
        if (!q->head)
            q->tail = NULL;
        job->next = NULL;
    }
    pthread_mutex_unlock(&q->lock);
    return job;
}

fc_render_job *fc_job_queue_take_all(fc_job_queue *q)
{
    pthread_mutex_lock(&q->lock);
    fc_render_job *list = q->head;
    q->head = q->tail = NULL;
    pthread_mutex_unlock(&q->lock);
    return list;
}

void fc_job_queue_close(fc_job_queue *q)
{
    pthread_mutex_lock(&q->lock);
    q->closed = true;
    pthread_cond_broadcast(&q->ready);
    pthread_mutex_unlock(&q->lock);
}
