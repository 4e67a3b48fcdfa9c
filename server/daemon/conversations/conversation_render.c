/* conversation_render.c — turning a client's state into render jobs; frames
 * becoming the client's current frame or its named session's newest. */
#include "conversations/conversation_internal.h"

#include <stdio.h>
#include <string.h>

#include "conversations/conversation_memory.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "monotonic.h"
#include "sessions/session.h"
#include "uploads/frame_pool.h"

/* What a frame decoded in place may keep beyond its arrays: the fixed part
 * of its message (16 bytes for FRAME, 48 for CHUNK) and the slack of a
 * recycled buffer (up to an eighth). */
#define PAYLOAD_SLACK_BYTES 64

fc_code fc_conversation_check_image_limit(const fc_limits *limits, uint32_t width, uint32_t height, fc_error *err)
{
    if (width <= limits->max_width && height <= limits->max_height)
        return FC_OK;
    return fc_error_set(err, FC_ERR_LIMIT, "image %ux%u exceeds this server's limit of %ux%u", (unsigned)width,
                        (unsigned)height, (unsigned)limits->max_width, (unsigned)limits->max_height);
}

fc_shared_frame *fc_conversation_current_frame(const fc_conversation *c)
{
    return c->session ? c->session->latest : c->frame;
}

fc_code fc_conversation_submit_render(fc_conversation *c, fc_shared_frame *frame, const fc_render_order *order,
                                      fc_error *err)
{
    fc_render_job *job = fc_render_job_create(frame);
    if (!job)
        return fc_error_set(err, FC_ERR_INTERNAL, "no memory for a render job");
    job->connection_id = c->connection_id;
    job->request_id = order->request_id;
    job->kind = order->kind;
    job->tag = order->tag;
    job->video = order->video ? fc_h264_stream_ref(order->video) : NULL;
    job->force_keyframe = order->force_keyframe;
    job->settings = c->settings;
    job->request = order->request;
    job->surface_attributes = order->surface_attributes;
    job->background = c->scene.background ? fc_scene_part_ref(c->scene.background) : NULL;
    job->environment = c->scene.environment ? fc_scene_part_ref(c->scene.environment) : NULL;
    /* A session's meshes (its producers') first, then the connection's own. */
    if (c->session)
        fc_mesh_set_append(&job->meshes, &c->session->meshes);
    fc_mesh_set_append(&job->meshes, &c->meshes);
    job->received_ms = order->received_ms;
    if (c->has_camera) {
        job->camera = c->camera;
    } else {
        /* Framed on the GL thread, which has time to measure the particles. */
        job->auto_camera = true;
        job->camera.width = order->auto_width;
        job->camera.height = order->auto_height;
    }
    fc_render_service_submit(c->ctx->render, job);
    return FC_OK;
}

static fc_code share_frame(fc_conversation *c, fc_frame_view *view, fc_foam_track *foam, uint64_t number,
                           double received_ms, double decode_ms, fc_shared_frame **out, fc_error *err)
{
    fc_code code = fc_shared_frame_create(view, c->ctx->frames, ++c->ctx->last_frame_id, foam, out, err);
    if (code != FC_OK)
        return code;
    (*out)->number = number;
    (*out)->ready_ms = fc_monotonic_ms();
    (*out)->receive_ms = (float)(received_ms - c->message_started_ms);
    (*out)->decode_ms = (float)decode_ms;
    return FC_OK;
}

/* The foam history a new frame continues: the named session's, or this
 * connection's own, begun with its first FRAME. */
static fc_code foam_history(fc_conversation *c, bool publishes, fc_foam_track **out, fc_error *err)
{
    if (publishes) {
        *out = c->session->foam;
        return FC_OK;
    }
    fc_code code = c->foam ? FC_OK : fc_foam_track_create(&c->foam, err);
    *out = c->foam;
    return code;
}

/* The frame a new one replaces must make room for it. */
static fc_code admit_frame(const fc_conversation *c, bool publishes, const fc_frame *frame, fc_error *err)
{
    const fc_shared_frame *replaced = publishes ? c->session->latest : c->frame;
    char what[64];
    snprintf(what, sizeof what, "a frame of %llu particles", (unsigned long long)frame->count);
    return fc_conversation_memory_admit(c, replaced ? fc_memory_of_frame(&replaced->frame) : 0,
                                        fc_memory_of_frame(frame), what, err);
}

fc_code fc_conversation_keep_payload(fc_conversation *c, fc_frame_view *view, fc_payload *payload, fc_error *err)
{
    if (view->block)
        return FC_OK;
    /* In place, the arrays lie back to back from the positions on. */
    size_t arrays = fc_frame_block_size(view->frame.count, fc_frame_attributes(&view->frame));
    if (payload->capacity - arrays <= PAYLOAD_SLACK_BYTES + arrays / 8) {
        *view = (fc_frame_view){view->frame, payload->bytes, payload->capacity};
        *payload = (fc_payload){NULL, 0};
        return FC_OK;
    }
    /* A buffer kept from a bigger message: the frame must not hold more than it counts. */
    uint8_t *block = fc_frame_pool_take(c->ctx->frames, arrays);
    if (!block)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a frame of %llu particles",
                            (unsigned long long)view->frame.count);
    memcpy(block, view->frame.positions, arrays);
    fc_frame frame;
    fc_frame_point_into_block(&frame, block, view->frame.count, fc_frame_attributes(&view->frame));
    *view = (fc_frame_view){frame, block, arrays};
    return FC_OK;
}

fc_code fc_conversation_take_frame(fc_conversation *c, fc_frame_view *view, fc_payload *payload, double received_ms,
                                   double decode_ms, fc_error *err)
{
    fc_code code = fc_conversation_keep_payload(c, view, payload, err);
    if (code != FC_OK)
        return code;
    if (c->role == FC_ROLE_VIEWER)
        code = fc_error_set(err, FC_ERR_BAD_STATE, "a viewer of session '%s' does not send frames", c->session->name);
    bool publishes = c->role == FC_ROLE_PRODUCER;
    fc_foam_track *foam = NULL;
    fc_shared_frame *shared;
    if (code == FC_OK)
        code = admit_frame(c, publishes, &view->frame, err);
    if (code == FC_OK)
        code = foam_history(c, publishes, &foam, err);
    if (code != FC_OK) {
        fc_frame_pool_give_view(c->ctx->frames, view);
        return code;
    }
    uint64_t number = publishes && c->session->latest ? c->session->latest->number + 1 : 1;
    code = share_frame(c, view, foam, publishes ? number : 0, received_ms, decode_ms, &shared, err);
    if (code != FC_OK)
        return code;
    if (publishes) {
        fc_session_publish(c->session, shared);
    } else {
        fc_shared_frame_unref(c->frame);
        c->frame = shared;
    }
    return FC_OK;
}
