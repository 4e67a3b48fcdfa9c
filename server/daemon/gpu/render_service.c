/* render_service.c — the GL thread and the plumbing around it (see render_service.h). */
#include "gpu/render_service.h"

#include <epoxy/gl.h>
#include <errno.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "gpu/encoder_pool.h"
#include "gpu/foam_apply.h"
#include "gpu/gpu_state.h"
#include "gpu/job_queue.h"
#include "gpu/surface_job.h"
#include "monotonic.h"

typedef struct gl_identity {
    char renderer[128];
    char egl_vendor[128];
    char gl_version[128];
    char device[256];
    char notes[2048];
    bool robust;
} gl_identity;

struct fc_render_service {
    fc_render_service_config config;
    fc_job_queue render_queue;       /* loop -> GL thread */
    fc_job_queue done;               /* GL thread / encoders -> loop */
    int wake_fd;
    fc_encoder_pool *encoders;
    pthread_t gl_thread;
    bool gl_running;
    /* startup handshake: the GL thread reports whether its context works */
    pthread_mutex_t start_lock;
    pthread_cond_t start_cond;
    bool start_reported;
    fc_error start_error;
    gl_identity identity;
    /* GL thread only */
    fc_gpu_state gpu;
    uint64_t renders;                /* requests that reached the GPU, for the lost-context test hook */
};

/* ---- GL thread ---- */

/* Radius 0 means "auto": each particle's own radius on a frame that has them
 * (the pipeline sizes them, PROTOCOL.md 5), else estimated once per frame,
 * however often it is rendered: by the pipeline when the frame is the one
 * uploaded (`uploaded`; its spray classes use the same estimate). */
static float resolve_radius(fc_render_job *job, fc_pipeline *uploaded)
{
    if (fc_radius_source_of(&job->settings, job->frame->frame.radius != NULL) != FC_RADIUS_ESTIMATED)
        return job->settings.radius;
    if (job->frame->estimated_radius <= 0.0f)
        job->frame->estimated_radius = uploaded ? fc_pipeline_estimated_radius(uploaded)
                                                : fc_frame_estimate_radius(&job->frame->frame);
    return job->frame->estimated_radius;
}

/* The pipeline holds the noise amplitudes of the uploaded frame only: every
 * upload gives the frame its own, from its stream's foam history. A render
 * with a density threshold reads the uploaded frame again (to sort it): it
 * is always this job's frame, which the job keeps referenced. */
static fc_code ensure_uploaded(fc_gpu_state *gpu, fc_shared_frame *frame, const fc_settings *settings,
                               float *upload_ms, fc_error *err)
{
    if (gpu->uploaded_frame_id == frame->id)
        return FC_OK;
    gpu->uploaded_frame_id = 0;
    fc_code code = fc_pipeline_upload(gpu->pipeline, &frame->frame, upload_ms, err);
    if (code == FC_OK)
        code = fc_foam_apply(frame, gpu->pipeline, settings, err);
    if (code == FC_OK)
        gpu->uploaded_frame_id = frame->id;
    return code;
}

/* Renders job->image and fills the GPU stages of job->stage_ms. */
static fc_code draw(fc_gpu_state *gpu, fc_render_job *job, fc_error *err)
{
    float render_ms[FC_STAGE_COUNT];
    fc_code code = ensure_uploaded(gpu, job->frame, &job->settings, &job->stage_ms[FC_STAGE_UPLOAD], err);
    if (code != FC_OK)
        return code;
    if (job->auto_camera)
        fc_camera_frame_bounds(&job->frame->frame, job->camera.width, job->camera.height, &job->camera);
    fc_settings settings = job->settings;
    settings.radius = resolve_radius(job, gpu->pipeline);
    /* RAW colour is RGBA8 and PNG/JPEG are 8-bit anyway; only EXR keeps linear floats. */
    int want_u8 = job->request.aov == FC_AOV_COLOR && job->request.format != FC_FORMAT_EXR;
    const fc_scene_textures *scene;
    code = fc_scene_texture_cache_get(&gpu->scene_textures, gpu->pipeline, job->background, job->environment,
                                      &scene, err);
    if (code != FC_OK)
        return code;
    fc_scene_mesh meshes[FC_MESH_SET_CAPACITY];
    code = fc_mesh_buffer_cache_scene(&gpu->meshes, gpu->pipeline, &job->meshes, meshes, err);
    if (code != FC_OK)
        return code;
    fc_render_scene with = {.textures = scene, .meshes = meshes, .mesh_count = job->meshes.count};
    code = fc_pipeline_render_with(gpu->pipeline, &job->camera, &settings, &with, job->request.aov, want_u8,
                                   &job->image, render_ms, err);
    if (code != FC_OK)
        return code;
    for (int s = FC_STAGE_DEPTH; s <= FC_STAGE_READBACK; s++)
        job->stage_ms[s] = render_ms[s];
    job->stage_ms[FC_STAGE_RECEIVE] = job->frame->receive_ms;
    job->stage_ms[FC_STAGE_DECODE] = job->frame->decode_ms;
    return FC_OK;
}

/* Back to the loop with job->error set. */
static void finish_failed(fc_render_service *rs, fc_render_job *job)
{
    fc_image_free(&job->image);
    fc_job_queue_push(&rs->done, job);
}

/* Replaces the pipeline's error with one that says what happened to "a
 * 640x480 image of 216 particles". */
static void explain_failure(fc_render_job *job, fc_gpu_failure failure, fc_gl_reset reset)
{
    char request[96];
    if (job->kind == FC_JOB_SURFACE)
        snprintf(request, sizeof request, "the surface of %llu particles",
                 (unsigned long long)job->frame->frame.count);
    else
        snprintf(request, sizeof request, "a %ux%u image of %llu particles", (unsigned)job->camera.width,
                 (unsigned)job->camera.height, (unsigned long long)job->frame->frame.count);
    fc_gpu_state_explain(failure, reset, request, &job->error);
}

/* The GPU's dedicated and available memory, for the metrics, where the
 * driver reports them (NVIDIA's GL_NVX_gpu_memory_info, in KiB); two integer
 * queries on the GL thread, after the render so they never delay one. */
static void report_gpu_memory(fc_metrics *metrics)
{
    enum { TOTAL_KIB = 0x9048, AVAILABLE_KIB = 0x9049 };   /* GL_GPU_MEMORY_INFO_*_NVX */
    if (!metrics || !epoxy_has_gl_extension("GL_NVX_gpu_memory_info"))
        return;
    GLint total = 0, available = 0;
    glGetIntegerv(TOTAL_KIB, &total);
    glGetIntegerv(AVAILABLE_KIB, &available);
    fc_metrics_set(metrics, FC_METRIC_GPU_MEMORY_TOTAL, (int64_t)total * 1024);
    fc_metrics_set(metrics, FC_METRIC_GPU_MEMORY_AVAILABLE, (int64_t)available * 1024);
}

static void render_job(fc_render_service *rs, fc_render_job *job)
{
    double start = fc_monotonic_ms();
    job->stage_ms[FC_STAGE_QUEUE] = (float)(start - job->submitted_ms);
    if (fc_gpu_state_acquire(&rs->gpu, start, &job->error) != FC_OK) {
        finish_failed(rs, job);
        return;
    }
    fc_code code = job->kind == FC_JOB_SURFACE
                       ? fc_surface_job_run(rs->gpu.pipeline, job, resolve_radius(job, NULL), &job->error)
                       : draw(&rs->gpu, job, &job->error);
    bool simulate_loss = ++rs->renders == rs->config.lose_context_at_render;
    fc_gl_reset reset;
    fc_gpu_failure failure = fc_gpu_state_diagnose(&rs->gpu, code, simulate_loss, &reset);
    if (code == FC_OK && failure == FC_GPU_FINE) {
        report_gpu_memory(rs->config.metrics);
        job->rendered_ms = fc_monotonic_ms();
        /* A surface reply is complete already; images go to an encoder. */
        if (job->kind == FC_JOB_SURFACE)
            fc_job_queue_push(&rs->done, job);
        else
            fc_encoder_pool_submit(rs->encoders, job);
        return;
    }
    if (failure != FC_GPU_FINE)
        explain_failure(job, failure, reset);
    finish_failed(rs, job);
    /* After the answer, so the requester does not wait for the recovery. */
    fc_gpu_state_recover(&rs->gpu, failure);
}

static void report_start(fc_render_service *rs, fc_code code, const fc_error *err)
{
    pthread_mutex_lock(&rs->start_lock);
    if (code != FC_OK)
        rs->start_error = *err;
    rs->start_reported = true;
    pthread_cond_signal(&rs->start_cond);
    pthread_mutex_unlock(&rs->start_lock);
}

static void *gl_main(void *arg)
{
    fc_render_service *rs = arg;
    fc_error err;
    fc_code code = fc_gpu_state_open(&rs->gpu, &rs->config.gpu, rs->config.shader_dir, rs->config.log, &err);
    if (code == FC_OK) {
        gl_identity *id = &rs->identity;
        snprintf(id->renderer, sizeof id->renderer, "%s", fc_gl_context_renderer(rs->gpu.gl));
        snprintf(id->egl_vendor, sizeof id->egl_vendor, "%s", fc_gl_context_egl_vendor(rs->gpu.gl));
        snprintf(id->gl_version, sizeof id->gl_version, "%s", fc_gl_context_version(rs->gpu.gl));
        snprintf(id->device, sizeof id->device, "%s", fc_gl_context_device(rs->gpu.gl));
        snprintf(id->notes, sizeof id->notes, "%s", fc_gl_context_notes(rs->gpu.gl));
        id->robust = fc_gl_context_robust(rs->gpu.gl);
    }
    report_start(rs, code, &err);
    if (code == FC_OK) {
        fc_render_job *job;
        while ((job = fc_job_queue_pop(&rs->render_queue)) != NULL)
            render_job(rs, job);
    }
    fc_gpu_state_close(&rs->gpu);
    return NULL;
}

/* ---- Loop side ---- */

static fc_code wait_for_gl(fc_render_service *rs, fc_error *err)
{
    pthread_mutex_lock(&rs->start_lock);
    while (!rs->start_reported)
        pthread_cond_wait(&rs->start_cond, &rs->start_lock);
    fc_error start_error = rs->start_error;
    pthread_mutex_unlock(&rs->start_lock);
    if (start_error.code == FC_OK)
        return FC_OK;
    if (err)
        *err = start_error;
    return start_error.code;
}

static fc_code start_threads(fc_render_service *rs, fc_error *err)
{
    if (pthread_create(&rs->gl_thread, NULL, gl_main, rs) != 0)
        return fc_error_set(err, FC_ERR_INTERNAL, "cannot start the GL thread: %s", strerror(errno));
    rs->gl_running = true;
    fc_code code = wait_for_gl(rs, err);
    if (code != FC_OK)
        return code;
    return fc_encoder_pool_create(rs->config.encoders, rs->config.png_compression, &rs->done, &rs->encoders, err);
}

fc_code fc_render_service_create(const fc_render_service_config *config, fc_render_service **out,
                                 fc_error *err)
{
    *out = NULL;
    fc_render_service *rs = calloc(1, sizeof *rs);
    if (!rs)
        return fc_error_set(err, FC_ERR_NOMEM, "render service: out of memory");
    rs->config = *config;
    rs->wake_fd = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    pthread_mutex_init(&rs->start_lock, NULL);
    pthread_cond_init(&rs->start_cond, NULL);
    fc_code code = rs->wake_fd >= 0 ? FC_OK : fc_error_set(err, FC_ERR_IO, "eventfd: %s", strerror(errno));
    if (code == FC_OK)
        code = fc_job_queue_init(&rs->render_queue, -1, err);
    if (code == FC_OK && (code = fc_job_queue_init(&rs->done, rs->wake_fd, err)) != FC_OK)
        fc_job_queue_destroy(&rs->render_queue);
    if (code != FC_OK) {
        if (rs->wake_fd >= 0)
            close(rs->wake_fd);
        free(rs);
        return code;
    }
    code = start_threads(rs, err);
    if (code != FC_OK) {
        fc_render_service_destroy(rs);
        return code;
    }
    *out = rs;
    return FC_OK;
}

void fc_render_service_destroy(fc_render_service *rs)
{
    if (!rs)
        return;
    fc_job_queue_close(&rs->render_queue);
    if (rs->gl_running)
        pthread_join(rs->gl_thread, NULL);
    /* After the GL thread: it is the one feeding the encoders. */
    fc_encoder_pool_destroy(rs->encoders);
    fc_job_queue_destroy(&rs->render_queue);
    fc_job_queue_destroy(&rs->done);
    pthread_cond_destroy(&rs->start_cond);
    pthread_mutex_destroy(&rs->start_lock);
    close(rs->wake_fd);
    free(rs);
}

const char *fc_render_service_renderer(const fc_render_service *rs)
{
    return rs->identity.renderer;
}

const char *fc_render_service_device(const fc_render_service *rs)
{
    return rs->identity.device;
}

const char *fc_render_service_gpu_notes(const fc_render_service *rs)
{
    return rs->identity.notes;
}

const char *fc_render_service_egl_vendor(const fc_render_service *rs)
{
    return rs->identity.egl_vendor;
}

const char *fc_render_service_gl_version(const fc_render_service *rs)
{
    return rs->identity.gl_version;
}

bool fc_render_service_robust(const fc_render_service *rs)
{
    return rs->identity.robust;
}

void fc_render_service_submit(fc_render_service *rs, fc_render_job *job)
{
    job->submitted_ms = fc_monotonic_ms();
    fc_job_queue_push(&rs->render_queue, job);
}

int fc_render_service_wake_fd(const fc_render_service *rs)
{
    return rs->wake_fd;
}

fc_render_job *fc_render_service_collect(fc_render_service *rs)
{
    uint64_t count;
    /* Cleared before taking, so a job pushed in between leaves the fd readable. */
    ssize_t got = read(rs->wake_fd, &count, sizeof count);
    (void)got;
    return fc_job_queue_take_all(&rs->done);
}
