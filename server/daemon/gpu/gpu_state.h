/* gpu_state.h — what the GL thread holds on the GPU (the EGL context, the
 * pipeline, the textures of clients' scene images, the frame uploaded last)
 * and how it recovers when a request fails on the GPU:
 *
 *   out of memory   the pipeline is rebuilt, which frees the render targets
 *                   the huge request allocated: GPU memory stays
 *                   proportional to the largest frame that succeeded;
 *   a GL error or   the context and the pipeline are destroyed and created
 *   a lost context  again.
 *
 * Everything that lived on the old context is forgotten: the uploaded frame
 * and the scene textures are made again from their CPU copies on next use, so
 * clients never notice beyond the one request that failed. When the GPU
 * cannot be brought back, every request is answered with ERROR RENDER and
 * creation is tried again on later requests, at most every
 * FC_GPU_RETRY_INTERVAL_MS. GL thread only. */
#ifndef FC_DAEMON_GPU_STATE_H
#define FC_DAEMON_GPU_STATE_H

#include <stdbool.h>
#include <stdint.h>

#include "gl/egl_context.h"
#include "gpu/mesh_buffer_cache.h"
#include "gpu/scene_texture_cache.h"
#include "log.h"
#include "render/pipeline.h"

/* A failed re-creation is not retried sooner, so a broken driver costs one
 * attempt per interval rather than one per request. */
#define FC_GPU_RETRY_INTERVAL_MS 2000.0

typedef enum fc_gpu_failure {
    FC_GPU_FINE = 0,
    FC_GPU_OUT_OF_MEMORY,    /* the request did not fit (FC_ERR_RENDER, FC_ERR_NOMEM) */
    FC_GPU_ERROR,            /* an unexpected GL error (FC_ERR_GL) */
    FC_GPU_CONTEXT_LOST      /* the context reports a reset */
} fc_gpu_failure;

typedef struct fc_gpu_state {
    fc_gpu_choice choice;
    const char *shader_dir;
    const fc_log *log;
    fc_gl_context *gl;                        /* NULL while the GPU is unavailable */
    fc_pipeline *pipeline;                    /* NULL while the GPU is unavailable */
    uint64_t uploaded_frame_id;               /* frame whose particles the pipeline holds; 0 = none */
    fc_scene_texture_cache scene_textures;    /* clients' background and cube map textures */
    fc_mesh_buffer_cache meshes;              /* clients' meshes on the GPU */
    fc_error unavailable;                     /* why the last re-creation failed */
    double retry_at_ms;                       /* no re-creation before this (fc_monotonic_ms) */
} fc_gpu_state;

/* Creates the context (current on the calling thread) and the pipeline. At
 * startup a failure is final: FC_ERR_GL with the reason. */
fc_code fc_gpu_state_open(fc_gpu_state *g, const fc_gpu_choice *choice, const char *shader_dir, const fc_log *log,
                          fc_error *err);
void fc_gpu_state_close(fc_gpu_state *g);

/* Before a request: FC_OK when context and pipeline are there. After a failed
 * re-creation they are created again once the retry interval has passed;
 * until they are, FC_ERR_RENDER saying the GPU is unavailable, and why. */
fc_code fc_gpu_state_acquire(fc_gpu_state *g, double now_ms, fc_error *err);

/* After a request ran and ended with `code`: whether the GPU failed, and how.
 * The context's reset status is asked every time (a reset can leave no GL
 * error behind); `simulate_loss` makes it answer an unknown reset (the
 * daemon's test hook). *reset receives the status. */
fc_gpu_failure fc_gpu_state_diagnose(const fc_gpu_state *g, fc_code code, bool simulate_loss, fc_gl_reset *reset);

/* The error the failed request is answered with: ERROR RENDER saying what
 * happened to `request` (e.g. "a 640x480 image of 216 particles"); *err holds
 * the pipeline's own error on entry. */
void fc_gpu_state_explain(fc_gpu_failure failure, fc_gl_reset reset, const char *request, fc_error *err);

/* Recovers from `failure` (see the top of this file; nothing to do for
 * FC_GPU_FINE), logging at warn level. */
void fc_gpu_state_recover(fc_gpu_state *g, fc_gpu_failure failure);

#endif
