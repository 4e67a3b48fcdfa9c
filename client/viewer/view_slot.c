/* view_slot.c — the request and image hand-over slots. */
#include "view_slot.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fc_error.h"

void fc_view_image_free(fc_view_image *image)
{
    free(image->rgba);
    image->rgba = NULL;
}

fc_code fc_view_slots_init(fc_view_slots *s, fc_error *err)
{
    memset(s, 0, sizeof *s);
    if (pthread_mutex_init(&s->lock, NULL) != 0)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot create a mutex");
    /* CLOCK_MONOTONIC for the timed wait, so a clock change cannot stall it. */
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    int rc = pthread_cond_init(&s->changed, &attr);
    pthread_condattr_destroy(&attr);
    if (rc != 0) {
        pthread_mutex_destroy(&s->lock);
        return fc_error_set(err, FC_ERR_NOMEM, "cannot create a condition variable");
    }
    return FC_OK;
}

void fc_view_slots_destroy(fc_view_slots *s)
{
    fc_view_image_free(&s->image);
    pthread_cond_destroy(&s->changed);
    pthread_mutex_destroy(&s->lock);
}

void fc_view_slots_put_request(fc_view_slots *s, const fc_view_request *r)
{
    pthread_mutex_lock(&s->lock);
    s->request = *r;
    pthread_cond_signal(&s->changed);
    pthread_mutex_unlock(&s->lock);
}

void fc_view_slots_stop(fc_view_slots *s)
{
    pthread_mutex_lock(&s->lock);
    s->stop = true;
    pthread_cond_signal(&s->changed);
    pthread_mutex_unlock(&s->lock);
}

bool fc_view_slots_take_image(fc_view_slots *s, fc_view_image *out)
{
    pthread_mutex_lock(&s->lock);
    bool have = s->image.rgba != NULL;
    if (have) {
        *out = s->image;
        s->image.rgba = NULL;
    }
    pthread_mutex_unlock(&s->lock);
    return have;
}

int fc_view_slots_failure(fc_view_slots *s, char *message, size_t size)
{
    pthread_mutex_lock(&s->lock);
    int status = s->failure_exit;
    snprintf(message, size, "%s", s->failure);
    pthread_mutex_unlock(&s->lock);
    return status;
}

fc_view_session_state fc_view_slots_session_state(fc_view_slots *s)
{
    pthread_mutex_lock(&s->lock);
    fc_view_session_state state = s->session_state;
    pthread_mutex_unlock(&s->lock);
    return state;
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

bool fc_view_slots_wait_request(fc_view_slots *s, uint64_t after, int timeout_ms, fc_view_request *out,
                                bool *stop)
{
    struct timespec deadline = deadline_after(timeout_ms < 0 ? 0 : timeout_ms);
    pthread_mutex_lock(&s->lock);
    int rc = 0;
    while (!s->stop && s->request.generation <= after && rc != ETIMEDOUT) {
        if (timeout_ms < 0)
            pthread_cond_wait(&s->changed, &s->lock);
        else
            rc = pthread_cond_timedwait(&s->changed, &s->lock, &deadline);
    }
    *stop = s->stop;
    bool fresh = !s->stop && s->request.generation > after;
    if (fresh)
        *out = s->request;
    pthread_mutex_unlock(&s->lock);
    return fresh;
}

void fc_view_slots_put_image(fc_view_slots *s, fc_view_image *image)
{
    pthread_mutex_lock(&s->lock);
    fc_view_image_free(&s->image);
    s->image = *image;
    image->rgba = NULL;
    pthread_mutex_unlock(&s->lock);
}

void fc_view_slots_fail(fc_view_slots *s, int exit_status, const char *message)
{
    pthread_mutex_lock(&s->lock);
    s->failure_exit = exit_status;
    snprintf(s->failure, sizeof s->failure, "%s", message);
    pthread_mutex_unlock(&s->lock);
}

void fc_view_slots_set_session_state(fc_view_slots *s, fc_view_session_state state)
{
    pthread_mutex_lock(&s->lock);
    s->session_state = state;
    pthread_mutex_unlock(&s->lock);
}
