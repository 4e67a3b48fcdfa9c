/* render_service.h — the daemon's rendering machinery: a dedicated GL thread
 * (the only thread that creates or uses the EGL context and the pipeline) fed
 * by a job queue, and an encoder pool that turns each rendered image into its
 * reply message while the GL thread renders the next. Finished jobs come back
 * to the event loop through a queue whose eventfd the loop polls. */
#ifndef FC_DAEMON_RENDER_SERVICE_H
#define FC_DAEMON_RENDER_SERVICE_H

#include <stdbool.h>
#include <stdint.h>

#include "gl/egl_context.h"
#include "gpu/render_job.h"
#include "log.h"
#include "metrics/metrics.h"

typedef struct fc_render_service fc_render_service;

typedef struct fc_render_service_config {
    fc_gpu_choice gpu;
    const char *shader_dir;   /* NULL: shaders built into the binary */
    unsigned encoders;        /* encoder threads, >= 1 */
    uint32_t png_compression; /* PNG's zlib level 0..9 (proto/image/image_encoder.h) */
    const fc_log *log;        /* GPU failures and recoveries are logged here */
    /* Test hook: the N-th request that reaches the GPU reports a lost context
     * (an unknown reset) and the real recovery follows; 0 = never. */
    uint64_t lose_context_at_render;
    /* Where the GL thread reports the GPU's memory after each render, when
     * the driver tells (GL_NVX_gpu_memory_info); NULL: nowhere. */
    fc_metrics *metrics;
} fc_render_service_config;

/* Starts the GL thread, waits until it has created the context and compiled
 * the pipeline (FC_ERR_GL with the reason when it cannot), then starts the
 * encoders. A request that fails on the GPU later (out of memory, a GL error,
 * a lost context) is answered with FC_ERR_RENDER and the GL thread recovers
 * (gpu_state.h); the service itself never stops for it. */
fc_code fc_render_service_create(const fc_render_service_config *config, fc_render_service **out,
                                 fc_error *err);
/* Stops the threads (jobs not yet rendered are dropped) and frees everything. */
void fc_render_service_destroy(fc_render_service *rs);

/* What the GL thread's context reported at startup. */
const char *fc_render_service_renderer(const fc_render_service *rs);
const char *fc_render_service_egl_vendor(const fc_render_service *rs);
const char *fc_render_service_gl_version(const fc_render_service *rs);
/* The device the context is on (fc_gl_context_device) and what choosing it
 * passed over, one warning a line (fc_gl_context_notes; "" when none). */
const char *fc_render_service_device(const fc_render_service *rs);
const char *fc_render_service_gpu_notes(const fc_render_service *rs);
/* Whether that context is robust (a GPU reset can be noticed and recovered from). */
bool fc_render_service_robust(const fc_render_service *rs);

/* Queues a job for the GL thread; the service owns it until it comes back
 * from fc_render_service_collect, rendered and encoded or with its error set. */
void fc_render_service_submit(fc_render_service *rs, fc_render_job *job);

/* Readable while finished jobs wait to be collected. */
int fc_render_service_wake_fd(const fc_render_service *rs);
/* The finished jobs as a list (oldest first), NULL when none; the caller frees them. */
fc_render_job *fc_render_service_collect(fc_render_service *rs);

#endif
