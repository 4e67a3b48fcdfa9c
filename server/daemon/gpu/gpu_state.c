/* gpu_state.c — see gpu_state.h. */
#include "gpu/gpu_state.h"

#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "gl/gpu_diagnosis.h"
#include "monotonic.h"

/* The textures were made through the pipeline and die with it; the uploaded
 * frame dies with it too. */
static void forget_pipeline(fc_gpu_state *g)
{
    fc_scene_texture_cache_free(&g->scene_textures);
    fc_mesh_buffer_cache_free(&g->meshes);
    fc_pipeline_destroy(g->pipeline);
    g->pipeline = NULL;
    g->uploaded_frame_id = 0;
}

static void release_all(fc_gpu_state *g)
{
    if (g->pipeline)
        forget_pipeline(g);
    fc_gl_context_destroy(g->gl);
    g->gl = NULL;
}

static fc_code create_pipeline(fc_gpu_state *g, fc_error *err)
{
    fc_pipeline_config config = {.shader_dir = g->shader_dir};
    return fc_pipeline_create(&config, &g->pipeline, err);
}

/* Loud, with the likely cause as this process sees it (gpu_diagnosis.h: the
 * container toolkit's capabilities, the NVIDIA EGL vendor file, /dev/dri and
 * its permissions): an operator who meant to render on a GPU (--gpu auto) is
 * rendering on the CPU, an order of magnitude slower. */
static void log_fallback(const fc_gpu_state *g)
{
    char causes[1024];
    fc_gpu_diagnose(causes, sizeof causes);
    fc_log_write(g->log, FC_LOG_WARN,
                 "--gpu auto: %s: rendering with Mesa's llvmpipe (software, on the CPU). Likely cause: %s. In a "
                 "container: the NVIDIA container toolkit (--gpus all / --runtime nvidia) with "
                 "NVIDIA_DRIVER_CAPABILITIES=graphics,utility, or --device /dev/dri. --gpu software silences this.",
                 fc_gl_context_fallback(g->gl), causes);
}

static fc_code create_all(fc_gpu_state *g, fc_error *err)
{
    fc_code code = fc_gl_context_create(&g->choice, &g->gl, err);
    if (code == FC_OK && fc_gl_context_fallback(g->gl)[0] != '\0')
        log_fallback(g);
    if (code == FC_OK)
        code = create_pipeline(g, err);
    if (code != FC_OK)
        release_all(g);
    return code;
}

fc_code fc_gpu_state_open(fc_gpu_state *g, const fc_gpu_choice *choice, const char *shader_dir, const fc_log *log,
                          fc_error *err)
{
    memset(g, 0, sizeof *g);
    g->choice = *choice;
    g->shader_dir = shader_dir;
    g->log = log;
    return create_all(g, err);
}

void fc_gpu_state_close(fc_gpu_state *g)
{
    release_all(g);
}

/* Destroys and creates context and pipeline; on failure the GPU stays
 * unavailable until the retry interval has passed. */
static fc_code recreate(fc_gpu_state *g, fc_error *err)
{
    double start = fc_monotonic_ms();
    release_all(g);
    fc_code code = create_all(g, err);
    if (code != FC_OK) {
        g->unavailable = *err;
        g->retry_at_ms = fc_monotonic_ms() + FC_GPU_RETRY_INTERVAL_MS;
        fc_log_write(g->log, FC_LOG_WARN, "GPU unavailable: %s; next attempt in %.0f ms", err->message,
                     FC_GPU_RETRY_INTERVAL_MS);
        return code;
    }
    fc_error_clear(&g->unavailable);
    fc_log_write(g->log, FC_LOG_WARN, "GPU context and pipeline created again in %.0f ms: %s, %s context",
                 fc_monotonic_ms() - start, fc_gl_context_renderer(g->gl),
                 fc_gl_context_robust(g->gl) ? "robust" : "plain");
    return FC_OK;
}

fc_code fc_gpu_state_acquire(fc_gpu_state *g, double now_ms, fc_error *err)
{
    if (g->pipeline)
        return FC_OK;
    if (now_ms < g->retry_at_ms)
        return fc_error_set(err, FC_ERR_RENDER, "the GPU is unavailable (%s); the server retries in %.0f ms",
                            g->unavailable.message, g->retry_at_ms - now_ms);
    fc_error why;
    if (recreate(g, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_RENDER, "the GPU is unavailable: %s", why.message);
    return FC_OK;
}

fc_gpu_failure fc_gpu_state_diagnose(const fc_gpu_state *g, fc_code code, bool simulate_loss, fc_gl_reset *reset)
{
    *reset = simulate_loss ? FC_GL_RESET_UNKNOWN : fc_gl_context_reset_status(g->gl);
    if (*reset != FC_GL_NO_RESET)
        return FC_GPU_CONTEXT_LOST;
    if (code == FC_ERR_GL)
        return FC_GPU_ERROR;
    if (code == FC_ERR_RENDER || code == FC_ERR_NOMEM)
        return FC_GPU_OUT_OF_MEMORY;
    return FC_GPU_FINE;
}

void fc_gpu_state_explain(fc_gpu_failure failure, fc_gl_reset reset, const char *request, fc_error *err)
{
    /* The cause is copied first: err is both the source and the result. */
    char cause[FC_ERROR_MESSAGE_MAX];
    snprintf(cause, sizeof cause, "%s", err->message);
    switch (failure) {
    case FC_GPU_CONTEXT_LOST:
        fc_error_set(err, FC_ERR_RENDER, "GPU context lost (%s reset) while rendering %s; the server recreates it",
                     fc_gl_reset_name(reset), request);
        break;
    case FC_GPU_ERROR:
        fc_error_set(err, FC_ERR_RENDER, "GPU error while rendering %s (%s); the server recreates its GPU context",
                     request, cause);
        break;
    case FC_GPU_OUT_OF_MEMORY:
        if (err->code == FC_ERR_NOMEM)
            fc_error_set(err, FC_ERR_RENDER, "out of memory for %s: %s", request, cause);
        else
            fc_error_set(err, FC_ERR_RENDER, "the GPU could not render %s: %s", request, cause);
        break;
    case FC_GPU_FINE:
        break;
    }
}

void fc_gpu_state_recover(fc_gpu_state *g, fc_gpu_failure failure)
{
    fc_error err;
    if (failure == FC_GPU_FINE)
        return;
    if (failure == FC_GPU_OUT_OF_MEMORY) {
        /* Rebuilding the pipeline frees every render target the request grew. */
        forget_pipeline(g);
        if (create_pipeline(g, &err) == FC_OK) {
            fc_log_write(g->log, FC_LOG_WARN, "GPU: pipeline rebuilt to release the memory of the failed request");
            return;
        }
        fc_log_write(g->log, FC_LOG_WARN, "GPU: rebuilding the pipeline failed (%s): recreating the context",
                     err.message);
    } else {
        fc_log_write(g->log, FC_LOG_WARN, "GPU: %s: recreating the context and the pipeline",
                     failure == FC_GPU_CONTEXT_LOST ? "context lost" : "unexpected GL error");
    }
    recreate(g, &err);
}
