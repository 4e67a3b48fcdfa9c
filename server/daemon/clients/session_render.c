/* session_render.c — turning a session's state into render jobs, and their
 * results back into replies; frames becoming current; the session's timers. */
#include "clients/session_internal.h"

#include <stdio.h>
#include <string.h>

#include "clients/session_memory.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "monotonic.h"
#include "sessions/stream_session.h"
#include "uploads/frame_pool.h"

/* What a frame decoded in place may keep beyond its arrays: the fixed part
 * of its message (16 bytes for FRAME, 48 for CHUNK) and the slack of a
 * recycled buffer (up to an eighth). */
#define PAYLOAD_SLACK_BYTES 64

void fc_session_send_error(fc_session *s, uint32_t request_id, const fc_error *err)
{
    fc_session_reply_error(s->ctx, s->peer, request_id, err, FC_SESSION_CONTINUE, s->out);
}

fc_code fc_session_queue_message(fc_session *s, const fc_buf *message, const char *what, fc_error *err)
{
    fc_code code = fc_session_memory_admit(s, 0, message->len, what, err);
    if (code != FC_OK)
        return code;
    if (!fc_buf_reserve(s->out, message->len)) {
        s->out->failed = false;
        return fc_error_set(err, FC_ERR_INTERNAL, "no memory to queue %s of %zu bytes", what, message->len);
    }
    memcpy(s->out->data + s->out->len, message->data, message->len);
    s->out->len += message->len;
    return FC_OK;
}

fc_shared_frame *fc_session_current_frame(const fc_session *s)
{
    return s->stream ? s->stream->latest : s->frame;
}

fc_code fc_session_submit_render(fc_session *s, fc_shared_frame *frame, const fc_render_order *order,
                                 fc_error *err)
{
    fc_render_job *job = fc_render_job_create(frame);
    if (!job)
        return fc_error_set(err, FC_ERR_INTERNAL, "no memory for a render job");
    job->connection_id = s->connection_id;
    job->request_id = order->request_id;
    job->kind = order->kind;
    job->tag = order->tag;
    job->settings = s->settings;
    job->request = order->request;
    job->background = s->scene.background ? fc_scene_part_ref(s->scene.background) : NULL;
    job->environment = s->scene.environment ? fc_scene_part_ref(s->scene.environment) : NULL;
    job->received_ms = order->received_ms;
    if (s->has_camera) {
        job->camera = s->camera;
    } else {
        /* Framed on the GL thread, which has time to measure the particles. */
        job->auto_camera = true;
        job->camera.width = order->auto_width;
        job->camera.height = order->auto_height;
    }
    fc_render_service_submit(s->ctx->render, job);
    return FC_OK;
}

static fc_code share_frame(fc_session *s, fc_frame_view *view, fc_foam_track *foam, uint64_t number,
                           double received_ms, double decode_ms, fc_shared_frame **out, fc_error *err)
{
    fc_code code = fc_shared_frame_create(view, s->ctx->frames, ++s->ctx->last_frame_id, foam, out, err);
    if (code != FC_OK)
        return code;
    (*out)->number = number;
    (*out)->ready_ms = fc_monotonic_ms();
    (*out)->receive_ms = (float)(received_ms - s->message_started_ms);
    (*out)->decode_ms = (float)decode_ms;
    return FC_OK;
}

/* The foam history a new frame continues: the named session's, or this
 * connection's own, begun with its first FRAME. */
static fc_code foam_history(fc_session *s, bool publishes, fc_foam_track **out, fc_error *err)
{
    if (publishes) {
        *out = s->stream->foam;
        return FC_OK;
    }
    fc_code code = s->foam ? FC_OK : fc_foam_track_create(&s->foam, err);
    *out = s->foam;
    return code;
}

/* The frame a new one replaces must make room for it. */
static fc_code admit_frame(const fc_session *s, bool publishes, const fc_frame *frame, fc_error *err)
{
    const fc_shared_frame *replaced = publishes ? s->stream->latest : s->frame;
    char what[64];
    snprintf(what, sizeof what, "a frame of %llu particles", (unsigned long long)frame->count);
    return fc_session_memory_admit(s, replaced ? fc_memory_of_frame(&replaced->frame) : 0, fc_memory_of_frame(frame),
                                   what, err);
}

fc_code fc_session_keep_payload(fc_session *s, fc_frame_view *view, fc_payload *payload, fc_error *err)
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
    uint8_t *block = fc_frame_pool_take(s->ctx->frames, arrays);
    if (!block)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a frame of %llu particles",
                            (unsigned long long)view->frame.count);
    memcpy(block, view->frame.positions, arrays);
    fc_frame frame;
    fc_frame_point_into_block(&frame, block, view->frame.count, fc_frame_attributes(&view->frame));
    *view = (fc_frame_view){frame, block, arrays};
    return FC_OK;
}

fc_code fc_session_take_frame(fc_session *s, fc_frame_view *view, fc_payload *payload, double received_ms,
                              double decode_ms, fc_error *err)
{
    fc_code code = fc_session_keep_payload(s, view, payload, err);
    if (code != FC_OK)
        return code;
    if (s->role == FC_ROLE_VIEWER)
        code = fc_error_set(err, FC_ERR_BAD_STATE, "a viewer of session '%s' does not send frames", s->stream->name);
    bool publishes = s->role == FC_ROLE_PRODUCER;
    fc_foam_track *foam = NULL;
    fc_shared_frame *shared;
    if (code == FC_OK)
        code = admit_frame(s, publishes, &view->frame, err);
    if (code == FC_OK)
        code = foam_history(s, publishes, &foam, err);
    if (code != FC_OK) {
        fc_frame_pool_give_view(s->ctx->frames, view);
        return code;
    }
    uint64_t number = publishes && s->stream->latest ? s->stream->latest->number + 1 : 1;
    code = share_frame(s, view, foam, publishes ? number : 0, received_ms, decode_ms, &shared, err);
    if (code != FC_OK)
        return code;
    if (publishes) {
        fc_stream_session_publish(s->stream, shared);
    } else {
        fc_shared_frame_unref(s->frame);
        s->frame = shared;
    }
    return FC_OK;
}

void fc_session_job_done(fc_session *s, const fc_render_job *job)
{
    if (job->kind == FC_JOB_STREAM) {
        fc_viewer_job_done(s, job);
        return;
    }
    s->reply_pending = false;
    if (job->error.code != FC_OK) {
        fc_session_send_error(s, job->request_id, &job->error);
        return;
    }
    fc_error err;
    /* A reply that does not fit leaves the queue as it was, so an ERROR can still follow. */
    if (fc_session_queue_message(s, &job->message, "the IMAGE", &err) != FC_OK) {
        fc_session_send_error(s, job->request_id, &err);
        return;
    }
    fc_log_write(s->ctx->log, FC_LOG_DEBUG, "%s: request %u: IMAGE of %zu bytes queued", s->peer,
                 (unsigned)job->request_id, job->message.len);
}

void fc_session_output_drained(fc_session *s)
{
    fc_viewer_drained(s);
}

size_t fc_session_backlog_allowance(const fc_session *s)
{
    return fc_viewer_backlog_allowance(s);
}

double fc_session_deadline_ms(const fc_session *s)
{
    return fc_viewer_deadline_ms(s);
}

void fc_session_tick(fc_session *s, double now_ms)
{
    fc_viewer_tick(s, now_ms);
}
