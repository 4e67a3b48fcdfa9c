/* encoder_pool.h — the threads that encode rendered images (image_encoder.h)
 * and build the reply messages, so encoding one frame overlaps rendering the
 * next. A PNG is deflated in strips on threads of its own besides
 * (png_encoder.h): one image can use the cores the GL thread leaves idle. */
#ifndef FC_DAEMON_ENCODER_POOL_H
#define FC_DAEMON_ENCODER_POOL_H

#include "gpu/job_queue.h"

typedef struct fc_encoder_pool fc_encoder_pool;

/* Starts `threads` encoders, writing PNGs at zlib level `png_compression`
 * (0..9); each finished job (message built, or error set) goes to `done`,
 * which must outlive the pool. */
fc_code fc_encoder_pool_create(unsigned threads, uint32_t png_compression, fc_job_queue *done,
                               fc_encoder_pool **out, fc_error *err);
/* Stops the threads after the jobs already submitted, and frees the pool. */
void fc_encoder_pool_destroy(fc_encoder_pool *pool);

/* Hands over a rendered job (job->image filled). */
void fc_encoder_pool_submit(fc_encoder_pool *pool, fc_render_job *job);

/* min(4, online cores), at least 1: the default thread count. */
unsigned fc_encoder_pool_default_threads(void);

#endif
