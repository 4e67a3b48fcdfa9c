/* render_reader.c — see render_reader.h. */
#include "render_reader.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "particle_reader.h"

struct fc_render_reader {
    char *const *paths;
    uint32_t count;
    const fc_read_options *options;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t changed;          /* an item was queued or taken, or stop/done was set */
    fc_read_frame queue[FC_RENDER_READ_AHEAD];
    uint32_t head, queued;           /* ring buffer */
    bool stop;                       /* the taker wants no more */
    bool done;                       /* the thread queues no more */
};

fc_code fc_load_particles_checked(const char *path, const fc_read_options *options, fc_frame *frame, fc_error *err)
{
    fc_code code = fc_read_particles_with(path, options, frame, err);
    if (code != FC_OK)
        return code;
    if (frame->count == 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s holds no particles", path);
    fc_error why;
    if (fc_frame_validate(frame, &why) != FC_OK)
        return fc_error_set(err, why.code, "%s: %s", path, why.message);
    return FC_OK;
}

/* Queues an item, waiting for room; false (the item freed) when stopped. */
static bool enqueue(fc_render_reader *r, fc_read_frame *item)
{
    pthread_mutex_lock(&r->lock);
    while (r->queued == FC_RENDER_READ_AHEAD && !r->stop)
        pthread_cond_wait(&r->changed, &r->lock);
    bool stopped = r->stop;
    if (!stopped) {
        r->queue[(r->head + r->queued) % FC_RENDER_READ_AHEAD] = *item;
        r->queued++;
        pthread_cond_broadcast(&r->changed);
    }
    pthread_mutex_unlock(&r->lock);
    if (stopped)
        fc_frame_free(&item->frame);
    return !stopped;
}

static void *read_all(void *arg)
{
    fc_render_reader *r = arg;
    for (uint32_t i = 0; i < r->count; i++) {
        fc_read_frame item = {.slot = i};
        item.code = fc_load_particles_checked(r->paths[i], r->options, &item.frame, &item.err);
        if (item.code != FC_OK)
            fc_frame_free(&item.frame);
        if (!enqueue(r, &item) || item.code != FC_OK)
            break;
    }
    pthread_mutex_lock(&r->lock);
    r->done = true;
    pthread_cond_broadcast(&r->changed);
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

fc_code fc_render_reader_start(char *const *paths, uint32_t count, const fc_read_options *options,
                              fc_render_reader **out, fc_error *err)
{
    *out = NULL;
    fc_render_reader *r = calloc(1, sizeof *r);
    if (!r)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the frame reader");
    r->paths = paths;
    r->count = count;
    r->options = options;
    pthread_mutex_init(&r->lock, NULL);
    pthread_cond_init(&r->changed, NULL);
    if (pthread_create(&r->thread, NULL, read_all, r) != 0) {
        pthread_cond_destroy(&r->changed);
        pthread_mutex_destroy(&r->lock);
        free(r);
        return fc_error_set(err, FC_ERR_IO, "cannot start the frame reader thread");
    }
    *out = r;
    return FC_OK;
}

bool fc_render_reader_next(fc_render_reader *r, fc_read_frame *out)
{
    pthread_mutex_lock(&r->lock);
    while (r->queued == 0 && !r->done)
        pthread_cond_wait(&r->changed, &r->lock);
    bool got = r->queued > 0;
    if (got) {
        *out = r->queue[r->head];
        r->head = (r->head + 1) % FC_RENDER_READ_AHEAD;
        r->queued--;
        pthread_cond_broadcast(&r->changed);
    }
    pthread_mutex_unlock(&r->lock);
    return got;
}

void fc_render_reader_stop(fc_render_reader *r)
{
    if (!r)
        return;
    pthread_mutex_lock(&r->lock);
    r->stop = true;
    pthread_cond_broadcast(&r->changed);
    pthread_mutex_unlock(&r->lock);
    pthread_join(r->thread, NULL);
    for (uint32_t k = 0; k < r->queued; k++)
        fc_frame_free(&r->queue[(r->head + k) % FC_RENDER_READ_AHEAD].frame);
    pthread_cond_destroy(&r->changed);
    pthread_mutex_destroy(&r->lock);
    free(r);
}
