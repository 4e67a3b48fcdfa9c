/* render_service.c — the GL thread and the plumbing around it (see render_service.h). */
#include "render_service.h"

#include <errno.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include "encoder_pool.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "foam_track.h"
#include "job_queue.h"
#include "monotonic.h"
#include "render/pipeline.h"
#include "scene_texture_cache.h"

typedef struct gl_identity {
    char renderer[128];
    char egl_vendor[128];
    char gl_version[128];
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
    fc_gl_context *gl;
    fc_pipeline *pipeline;
    uint64_t uploaded_frame_id;      /* frame whose particles the pipeline holds; 0 = none or unknown */
    fc_scene_texture_cache scene_textures;   /* clients' background and cube map textures */
};

/* ---- GL thread ---- */

/* Radius 0 means "auto": estimated once per frame, however often it is rendered. */
static float resolve_radius(fc_render_job *job)
{
    if (job->settings.radius > 0.0f)
        return job->settings.radius;
    if (job->frame->estimated_radius <= 0.0f)
        job->frame->estimated_radius = fc_frame_estimate_radius(&job->frame->frame);
    return job->frame->estimated_radius;
}

/* The pipeline holds the noise amplitudes of the uploaded frame only: every
 * upload gives the frame its own, from its stream's foam history. */
static fc_code ensure_uploaded(fc_render_service *rs, fc_shared_frame *frame, const fc_settings *settings,
                               float *upload_ms, fc_error *err)
{
    if (rs->uploaded_frame_id == frame->id)
        return FC_OK;
    rs->uploaded_frame_id = 0;
    fc_code code = fc_pipeline_upload(rs->pipeline, &frame->frame, upload_ms, err);
    if (code == FC_OK)
        code = fc_foam_track_apply(frame, rs->pipeline, settings, err);
    if (code == FC_OK)
        rs->uploaded_frame_id = frame->id;
    return code;
}

/* Renders job->image and fills the GPU stages of job->stage_ms. */
static fc_code draw(fc_render_service *rs, fc_render_job *job, fc_error *err)
{
    float render_ms[FC_STAGE_COUNT];
    fc_code code = ensure_uploaded(rs, job->frame, &job->settings, &job->stage_ms[FC_STAGE_UPLOAD], err);
    if (code != FC_OK)
        return code;
    if (job->auto_camera)
        fc_camera_frame_bounds(&job->frame->frame, job->camera.width, job->camera.height, &job->camera);
    fc_settings settings = job->settings;
    settings.radius = resolve_radius(job);
    /* RAW colour is RGBA8 and PNG/JPEG are 8-bit anyway; only EXR keeps linear floats. */
    int want_u8 = job->request.aov == FC_AOV_COLOR && job->request.format != FC_FORMAT_EXR;
    const fc_scene_textures *scene;
    code = fc_scene_texture_cache_get(&rs->scene_textures, rs->pipeline, job->background, job->environment, &scene,
                                      err);
    if (code != FC_OK)
        return code;
    code = fc_pipeline_render_scene(rs->pipeline, &job->camera, &settings, scene, job->request.aov, want_u8,
                                    &job->image, render_ms, err);
    if (code != FC_OK)
        return code;
    for (int s = FC_STAGE_DEPTH; s <= FC_STAGE_READBACK; s++)
        job->stage_ms[s] = render_ms[s];
    job->stage_ms[FC_STAGE_RECEIVE] = job->frame->receive_ms;
    job->stage_ms[FC_STAGE_DECODE] = job->frame->decode_ms;
    return FC_OK;
}

static void render_job(fc_render_service *rs, fc_render_job *job)
{
    double start = fc_monotonic_ms();
    job->stage_ms[FC_STAGE_QUEUE] = (float)(start - job->submitted_ms);
    if (draw(rs, job, &job->error) != FC_OK) {
        fc_image_free(&job->image);
        fc_job_queue_push(&rs->done, job);
        return;
    }
    job->rendered_ms = fc_monotonic_ms();
    fc_encoder_pool_submit(rs->encoders, job);
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

static fc_code start_gl(fc_render_service *rs, fc_error *err)
{
    fc_code code = fc_gl_context_create(&rs->config.gpu, &rs->gl, err);
    if (code != FC_OK)
        return code;
    fc_pipeline_config pipeline_config = {rs->config.shader_dir};
    code = fc_pipeline_create(&pipeline_config, &rs->pipeline, err);
    if (code != FC_OK)
        return code;
    snprintf(rs->identity.renderer, sizeof rs->identity.renderer, "%s", fc_gl_context_renderer(rs->gl));
    snprintf(rs->identity.egl_vendor, sizeof rs->identity.egl_vendor, "%s", fc_gl_context_egl_vendor(rs->gl));
    snprintf(rs->identity.gl_version, sizeof rs->identity.gl_version, "%s", fc_gl_context_version(rs->gl));
    return FC_OK;
}

static void stop_gl(fc_render_service *rs)
{
    /* The pipeline's GL objects die with the context: destroy them first. */
    fc_scene_texture_cache_free(&rs->scene_textures);
    if (rs->pipeline)
        fc_pipeline_destroy(rs->pipeline);
    if (rs->gl)
        fc_gl_context_destroy(rs->gl);
    rs->pipeline = NULL;
    rs->gl = NULL;
}

static void *gl_main(void *arg)
{
    fc_render_service *rs = arg;
    fc_error err;
    fc_code code = start_gl(rs, &err);
    report_start(rs, code, &err);
    if (code == FC_OK) {
        fc_render_job *job;
        while ((job = fc_job_queue_pop(&rs->render_queue)) != NULL)
            render_job(rs, job);
    }
    stop_gl(rs);
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
    return fc_encoder_pool_create(rs->config.encoders, &rs->done, &rs->encoders, err);
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

const char *fc_render_service_egl_vendor(const fc_render_service *rs)
{
    return rs->identity.egl_vendor;
}

const char *fc_render_service_gl_version(const fc_render_service *rs)
{
    return rs->identity.gl_version;
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
