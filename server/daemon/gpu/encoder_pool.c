/* encoder_pool.c — see encoder_pool.h. */
#include "gpu/encoder_pool.h"

#include <stdlib.h>
#include <unistd.h>

#include "image_encoder.h"
#include "fc_error.h"
#include "gpu/h264_stream.h"
#include "monotonic.h"

enum { MAX_DEFAULT_ENCODERS = 4 };

struct fc_encoder_pool {
    fc_job_queue todo;
    fc_job_queue *done;
    uint32_t png_compression;
    pthread_t *threads;
    unsigned started;
};

unsigned fc_encoder_pool_default_threads(void)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (cores < 1)
        return 1;
    return cores < MAX_DEFAULT_ENCODERS ? (unsigned)cores : MAX_DEFAULT_ENCODERS;
}

static fc_code build_message(fc_render_job *job, const fc_buf *encoded)
{
    fc_image_reply reply = {0};
    reply.width = job->image.width;
    reply.height = job->image.height;
    reply.format = job->request.format;
    reply.aov = job->request.aov;
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        reply.stage_ms[s] = job->stage_ms[s];
    reply.data = encoded->data;
    reply.size = encoded->len;
    if (job->kind == FC_JOB_STREAM)
        return fc_wire_write_stream_image(&job->message, job->request_id, &job->tag, &reply, &job->error);
    return fc_wire_write_image(&job->message, job->request_id, &reply, &job->error);
}

/* H.264: the next access unit of the viewer's stream, or an IDR frame of its own for a RENDER. */
static fc_code encode_h264(fc_render_job *job, fc_buf *encoded)
{
    if (!job->video) {
        job->tag.flags |= FC_STREAM_KEYFRAME;
        return fc_h264_encode_single(&job->image, job->request.quality, encoded, &job->error);
    }
    bool keyframe;
    fc_code code = fc_h264_stream_encode(job->video, &job->image, job->force_keyframe, encoded, &keyframe,
                                         &job->error);
    if (keyframe)
        job->tag.flags |= FC_STREAM_KEYFRAME;
    return code;
}

/* Encodes the image and builds the message; on failure job->error says why. */
static void encode_job(const fc_encoder_pool *pool, fc_render_job *job, fc_buf *encoded)
{
    double start = fc_monotonic_ms();
    job->stage_ms[FC_STAGE_QUEUE] += (float)(start - job->rendered_ms);
    fc_buf_reset(encoded);
    fc_encode_options options = {job->request.quality, pool->png_compression, job->settings.jpeg_subsampling};
    fc_code code = job->request.format == FC_FORMAT_H264
                       ? encode_h264(job, encoded)
                       : fc_encode_image_with(&job->image, job->request.format, &options, encoded, &job->error);
    if (code != FC_OK)
        return;
    double end = fc_monotonic_ms();
    job->stage_ms[FC_STAGE_ENCODE] = (float)(end - start);
    job->stage_ms[FC_STAGE_TOTAL] = (float)(end - job->received_ms);
    if (build_message(job, encoded) != FC_OK)
        fc_buf_free(&job->message);
}

static void *encoder_main(void *arg)
{
    fc_encoder_pool *pool = arg;
    /* One buffer per thread, reused: encoded files are copied into the message. */
    fc_buf encoded;
    fc_buf_init(&encoded);
    fc_render_job *job;
    while ((job = fc_job_queue_pop(&pool->todo)) != NULL) {
        encode_job(pool, job, &encoded);
        fc_image_free(&job->image);
        fc_job_queue_push(pool->done, job);
    }
    fc_buf_free(&encoded);
    return NULL;
}

fc_code fc_encoder_pool_create(unsigned threads, uint32_t png_compression, fc_job_queue *done,
                               fc_encoder_pool **out, fc_error *err)
{
    *out = NULL;
    fc_encoder_pool *pool = calloc(1, sizeof *pool);
    if (!pool)
        return fc_error_set(err, FC_ERR_NOMEM, "encoder pool: out of memory");
    pool->done = done;
    pool->png_compression = png_compression;
    fc_code code = fc_job_queue_init(&pool->todo, -1, err);
    if (code != FC_OK) {
        free(pool);
        return code;
    }
    pool->threads = calloc(threads, sizeof *pool->threads);
    if (!pool->threads)
        code = fc_error_set(err, FC_ERR_NOMEM, "encoder pool: out of memory");
    for (unsigned i = 0; code == FC_OK && i < threads; i++) {
        if (pthread_create(&pool->threads[i], NULL, encoder_main, pool) != 0)
            code = fc_error_set(err, FC_ERR_INTERNAL, "cannot start encoder thread %u", i);
        else
            pool->started++;
    }
    if (code != FC_OK) {
        fc_encoder_pool_destroy(pool);
        return code;
    }
    *out = pool;
    return FC_OK;
}

void fc_encoder_pool_destroy(fc_encoder_pool *pool)
{
    if (!pool)
        return;
    fc_job_queue_close(&pool->todo);
    for (unsigned i = 0; i < pool->started; i++)
        pthread_join(pool->threads[i], NULL);
    fc_job_queue_destroy(&pool->todo);
    free(pool->threads);
    free(pool);
}

void fc_encoder_pool_submit(fc_encoder_pool *pool, fc_render_job *job)
{
    fc_job_queue_push(&pool->todo, job);
}
