/* render_service.h — everything GPU-side the daemon does for a RENDER: owns the
 * GL context and the pipeline, resolves the radius, uploads, renders, encodes
 * and builds the IMAGE reply. Today it runs on the event-loop thread (where the
 * context is current); callers only see jobs and replies, so it can move to a
 * GL thread with an encoder pool without changing them. */
#ifndef FC_DAEMON_RENDER_SERVICE_H
#define FC_DAEMON_RENDER_SERVICE_H

#include <stdint.h>

#include "gl/egl_context.h"
#include "wire.h"

typedef struct fc_render_service fc_render_service;

/* A client's current frame, with what the service derives from it once. */
typedef struct fc_scene {
    fc_frame frame;
    uint64_t frame_id;        /* from fc_render_service_new_frame_id: tells whether it is on the GPU */
    float estimated_radius;   /* 0 until a render with radius "auto" estimated it */
} fc_scene;

typedef struct fc_render_job {
    fc_scene *scene;               /* estimated_radius is filled in when needed */
    const fc_camera *camera;
    const fc_settings *settings;
    fc_render_request request;
    double received_ms;            /* fc_monotonic_ms() when the RENDER arrived, for FC_STAGE_TOTAL */
} fc_render_job;

/* Creates the GL context (current on the calling thread) and compiles the
 * pipeline. shader_dir NULL: built-in shaders. */
fc_code fc_render_service_create(const fc_gpu_choice *gpu, const char *shader_dir, fc_render_service **out,
                                 fc_error *err);
void fc_render_service_destroy(fc_render_service *rs);

const fc_gl_context *fc_render_service_gl(const fc_render_service *rs);

/* A process-unique id for a newly received frame (never 0). */
uint64_t fc_render_service_new_frame_id(fc_render_service *rs);

/* Renders the job and appends an IMAGE message answering request_id to out.
 * On failure appends nothing: FC_ERR_GL/FC_ERR_RENDER, FC_ERR_ENCODE or
 * FC_ERR_NOMEM with the reason. */
fc_code fc_render_service_render(fc_render_service *rs, const fc_render_job *job, uint32_t request_id,
                                 fc_buf *out, fc_error *err);

#endif
