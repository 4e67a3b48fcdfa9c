/* render_service.c — GL context + pipeline + encoder behind one render call. */
#include "render_service.h"

#include <stdlib.h>

#include "encode/image_encoder.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "monotonic.h"
#include "render/pipeline.h"

struct fc_render_service {
    fc_gl_context *gl;
    fc_pipeline *pipeline;
    uint64_t last_frame_id;
    uint64_t uploaded_frame_id;   /* frame whose particles the pipeline holds; 0 = none or unknown */
    fc_image image;               /* read-back pixels, reused across renders */
    fc_buf encoded;               /* encoded file, reused across renders */
};

fc_code fc_render_service_create(const fc_gpu_choice *gpu, const char *shader_dir, fc_render_service **out,
                                 fc_error *err)
{
    *out = NULL;
    fc_render_service *rs = calloc(1, sizeof *rs);
    if (!rs)
        return fc_error_set(err, FC_ERR_NOMEM, "render service: out of memory");
    fc_buf_init(&rs->encoded);
    fc_code code = fc_gl_context_create(gpu, &rs->gl, err);
    if (code == FC_OK) {
        fc_pipeline_config config = {shader_dir};
        code = fc_pipeline_create(&config, &rs->pipeline, err);
    }
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
    /* The pipeline's GL objects die with the context: destroy them first. */
    if (rs->pipeline)
        fc_pipeline_destroy(rs->pipeline);
    if (rs->gl)
        fc_gl_context_destroy(rs->gl);
    fc_image_free(&rs->image);
    fc_buf_free(&rs->encoded);
    free(rs);
}

const fc_gl_context *fc_render_service_gl(const fc_render_service *rs)
{
    return rs->gl;
}

uint64_t fc_render_service_new_frame_id(fc_render_service *rs)
{
    return ++rs->last_frame_id;
}

/* Radius 0 means "auto": estimated once per frame, however often it is rendered. */
static float resolve_radius(const fc_render_job *job)
{
    if (job->settings->radius > 0.0f)
        return job->settings->radius;
    if (job->scene->estimated_radius <= 0.0f)
        job->scene->estimated_radius = fc_frame_estimate_radius(&job->scene->frame);
    return job->scene->estimated_radius;
}

/* Uploads the job's frame unless the pipeline already holds it. */
static fc_code ensure_uploaded(fc_render_service *rs, const fc_scene *scene, float *upload_ms, fc_error *err)
{
    if (rs->uploaded_frame_id == scene->frame_id)
        return FC_OK;
    rs->uploaded_frame_id = 0;
    fc_code code = fc_pipeline_upload(rs->pipeline, &scene->frame, upload_ms, err);
    if (code == FC_OK)
        rs->uploaded_frame_id = scene->frame_id;
    return code;
}

static void mark_unmeasured(float *stage_ms)
{
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        stage_ms[s] = -1.0f;
}

/* Draws and reads back the requested image; fills the GPU stages of stage_ms. */
static fc_code draw(fc_render_service *rs, const fc_render_job *job, float *stage_ms, fc_error *err)
{
    float upload_ms[FC_STAGE_COUNT];
    float render_ms[FC_STAGE_COUNT];
    mark_unmeasured(upload_ms);
    mark_unmeasured(render_ms);
    fc_code code = ensure_uploaded(rs, job->scene, upload_ms, err);
    if (code != FC_OK)
        return code;
    fc_settings settings = *job->settings;
    settings.radius = resolve_radius(job);
    /* RAW colour is RGBA8 and PNG/JPEG are 8-bit anyway; only EXR keeps linear floats. */
    int want_u8 = job->request.aov == FC_AOV_COLOR && job->request.format != FC_FORMAT_EXR;
    code = fc_pipeline_render(rs->pipeline, job->camera, &settings, job->request.aov, want_u8, &rs->image,
                              render_ms, err);
    if (code != FC_OK)
        return code;
    stage_ms[FC_STAGE_UPLOAD] = upload_ms[FC_STAGE_UPLOAD];
    for (int s = FC_STAGE_DEPTH; s <= FC_STAGE_READBACK; s++)
        stage_ms[s] = render_ms[s];
    return FC_OK;
}

fc_code fc_render_service_render(fc_render_service *rs, const fc_render_job *job, uint32_t request_id,
                                 fc_buf *out, fc_error *err)
{
    fc_image_reply reply = {0};
    mark_unmeasured(reply.stage_ms);
    fc_code code = draw(rs, job, reply.stage_ms, err);
    if (code != FC_OK)
        return code;
    double encode_start = fc_monotonic_ms();
    fc_buf_reset(&rs->encoded);
    code = fc_encode_image(&rs->image, job->request.format, job->request.quality, &rs->encoded, err);
    if (code != FC_OK)
        return code;
    double encoded_at = fc_monotonic_ms();
    reply.stage_ms[FC_STAGE_ENCODE] = (float)(encoded_at - encode_start);
    reply.stage_ms[FC_STAGE_TOTAL] = (float)(encoded_at - job->received_ms);
    reply.width = rs->image.width;
    reply.height = rs->image.height;
    reply.format = job->request.format;
    reply.aov = job->request.aov;
    reply.data = rs->encoded.data;
    reply.size = rs->encoded.len;
    size_t len_before = out->len;
    code = fc_wire_write_image(out, request_id, &reply, err);
    if (code != FC_OK) {
        /* The reply did not fit: leave the queue as it was, so an ERROR can still follow. */
        out->len = len_before;
        out->failed = false;
    }
    return code;
}
