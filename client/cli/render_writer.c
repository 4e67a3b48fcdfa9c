/* render_writer.c — see render_writer.h. A bounded ring of images between the
 * connection's thread (the producer) and the writer thread (the consumer). */
#include "render_writer.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>

#include "fc_error.h"

typedef struct queued_image {
    uint32_t number;
    fc_image_result image;
} queued_image;

struct fc_render_writer {
    fc_render_output *output;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t changed;      /* an image was queued or taken, or closing was set */
    queued_image queue[FC_RENDER_WRITE_BEHIND];
    uint32_t head, queued;
    bool writing;                /* the thread holds an image it took */
    bool closing;                /* nothing more will be put */
    uint32_t written;
    fc_error failure;            /* the first failure: code FC_OK while there is none */
};

/* Takes the next image; false when the queue is empty and closing. */
static bool take(fc_render_writer *w, queued_image *out)
{
    pthread_mutex_lock(&w->lock);
    while (w->queued == 0 && !w->closing)
        pthread_cond_wait(&w->changed, &w->lock);
    bool got = w->queued > 0;
    if (got) {
        *out = w->queue[w->head];
        w->head = (w->head + 1) % FC_RENDER_WRITE_BEHIND;
        w->queued--;
        w->writing = true;
        pthread_cond_broadcast(&w->changed);
    }
    pthread_mutex_unlock(&w->lock);
    return got;
}

static void *write_all(void *arg)
{
    fc_render_writer *w = arg;
    queued_image item;
    while (take(w, &item)) {
        fc_error err = {FC_OK, ""};
        /* After a failure the rest is dropped: a video must not skip a frame. */
        bool failed_before = w->failure.code != FC_OK;
        fc_code code = failed_before ? FC_OK : fc_render_output_write(w->output, item.number, &item.image, &err);
        fc_image_result_free(&item.image);
        pthread_mutex_lock(&w->lock);
        if (code != FC_OK)
            w->failure = err;
        else if (!failed_before)
            w->written++;
        w->writing = false;
        pthread_cond_broadcast(&w->changed);
        pthread_mutex_unlock(&w->lock);
    }
    return NULL;
}

fc_code fc_render_writer_start(fc_render_output *output, fc_render_writer **out, fc_error *err)
{
    *out = NULL;
    fc_render_writer *w = calloc(1, sizeof *w);
    if (!w)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the image writer");
    w->output = output;
    w->failure.code = FC_OK;
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->changed, NULL);
    if (pthread_create(&w->thread, NULL, write_all, w) != 0) {
        pthread_cond_destroy(&w->changed);
        pthread_mutex_destroy(&w->lock);
        free(w);
        return fc_error_set(err, FC_ERR_IO, "cannot start the image writer thread");
    }
    *out = w;
    return FC_OK;
}

fc_code fc_render_writer_put(fc_render_writer *w, uint32_t number, fc_image_result *image, fc_error *err)
{
    pthread_mutex_lock(&w->lock);
    while (w->queued == FC_RENDER_WRITE_BEHIND && w->failure.code == FC_OK)
        pthread_cond_wait(&w->changed, &w->lock);
    fc_error failure = w->failure;
    if (failure.code == FC_OK) {
        queued_image *slot = &w->queue[(w->head + w->queued) % FC_RENDER_WRITE_BEHIND];
        slot->number = number;
        slot->image = *image;
        *image = (fc_image_result){0};
        w->queued++;
        pthread_cond_broadcast(&w->changed);
    }
    pthread_mutex_unlock(&w->lock);
    if (failure.code == FC_OK)
        return FC_OK;
    fc_image_result_free(image);
    *err = failure;
    return failure.code;
}

fc_code fc_render_writer_finish(fc_render_writer *w, uint32_t *written, fc_error *err)
{
    pthread_mutex_lock(&w->lock);
    w->closing = true;
    pthread_cond_broadcast(&w->changed);
    pthread_mutex_unlock(&w->lock);
    pthread_join(w->thread, NULL);
    *written = w->written;
    fc_code code = w->failure.code;
    if (code != FC_OK)
        *err = w->failure;
    pthread_cond_destroy(&w->changed);
    pthread_mutex_destroy(&w->lock);
    free(w);
    return code;
}
