/* viewer.c — see viewer.h. */
#include "conversations/viewer.h"

#include <string.h>

#include "conversations/conversation_internal.h"
#include "fc_error.h"
#include "monotonic.h"
#include "sessions/session.h"

typedef enum image_reason {
    REASON_NEW_FRAME = 0,    /* the session published a frame this viewer has not seen */
    REASON_VIEW,             /* the viewer's camera or settings changed */
    REASON_REFRESH           /* lossless copy of a frame shown lossy */
} image_reason;

static bool is_viewer(const struct fc_conversation *c)
{
    return c->role == FC_ROLE_VIEWER;
}

static fc_render_order order_for(const struct fc_conversation *c, image_reason reason, double now_ms)
{
    const fc_viewer *v = &c->viewer;
    const fc_session *session = c->session;
    fc_render_order order = {0};
    order.kind = FC_JOB_STREAM;
    order.request_id = v->subscribe_id;
    order.request = v->request;
    order.auto_width = v->auto_width;
    order.auto_height = v->auto_height;
    order.tag.frame_number = session->latest->number;
    order.tag.sequence = session->sequence;
    if (reason == REASON_NEW_FRAME) {
        uint64_t missed = session->sequence - v->last_sequence - 1;
        order.tag.missed = missed > UINT32_MAX ? UINT32_MAX : (uint32_t)missed;
        order.received_ms = session->latest->ready_ms;
    } else if (reason == REASON_VIEW) {
        order.tag.flags = FC_STREAM_VIEW;
        order.received_ms = v->view_changed_ms;
    } else {
        order.tag.flags = FC_STREAM_REFRESH;
        order.request.format = FC_FORMAT_PNG;
        order.received_ms = now_ms;
    }
    /* Frames the viewer missed were never encoded for it, so its decoder is
     * still in step with the encoder: only a lost access unit or the
     * client's request needs an IDR (a new stream or size makes one anyway). */
    if (order.request.format == FC_FORMAT_H264) {
        order.video = v->video;
        order.force_keyframe = v->keyframe_wanted;
    }
    return order;
}

static void dispatch(struct fc_conversation *c, image_reason reason, double now_ms)
{
    fc_viewer *v = &c->viewer;
    fc_render_order order = order_for(c, reason, now_ms);
    fc_error err;
    if (fc_conversation_submit_render(c, c->session->latest, &order, &err) != FC_OK) {
        fc_conversation_send_error(c, v->subscribe_id, &err);
        return;
    }
    v->busy = true;
    v->view_changed = false;
    if (order.request.format == FC_FORMAT_H264)
        v->keyframe_wanted = false;
    v->last_sequence = c->session->sequence;
    fc_metrics_add(c->ctx->metrics, FC_METRIC_DROPPED_VIEWER_BUSY, order.tag.missed);
    double refresh_ms = c->ctx->refresh_ms;
    bool lossy = order.request.format == FC_FORMAT_JPEG || order.request.format == FC_FORMAT_H264;
    v->refresh_due_ms = lossy && refresh_ms > 0.0 ? now_ms + refresh_ms : 0.0;
}

/* Answers the client's SESSION_END and leaves the session. */
static void send_leave_answer(struct fc_conversation *c)
{
    fc_error err;
    fc_session *session = c->session;
    if (fc_wire_write_session_end(c->out, c->viewer.end_request_id, session->name, &err) != FC_OK)
        fc_log_write(c->ctx->log, FC_LOG_ERROR, "%s: cannot queue SESSION_END: %s", c->peer, err.message);
    fc_log_write(c->ctx->log, FC_LOG_INFO, "%s: left session '%s' as a viewer", c->peer, session->name);
    fc_viewer_detach(c);
}

/* Tells the viewer that its session ended; it stays on the last frame. The
 * refresh of an image made before the end is dropped: after SESSION_END only
 * the viewer's own view changes make images (PROTOCOL.md 10.1). */
static void send_ended_notice(struct fc_conversation *c)
{
    fc_error err;
    fc_viewer *v = &c->viewer;
    if (fc_wire_write_session_end(c->out, v->subscribe_id, c->session->name, &err) != FC_OK)
        fc_log_write(c->ctx->log, FC_LOG_ERROR, "%s: cannot queue SESSION_END: %s", c->peer, err.message);
    v->told_ended = true;
    v->refresh_due_ms = 0.0;
}

/* Starts the next image this viewer is due, or answers its leaving, or tells it the session ended. */
static void pump(struct fc_conversation *c, double now_ms)
{
    fc_viewer *v = &c->viewer;
    if (!is_viewer(c) || v->busy)
        return;
    const fc_session *session = c->session;
    bool new_frame = session->latest && session->sequence > v->last_sequence;
    if (v->leaving)
        send_leave_answer(c);
    else if (new_frame)
        dispatch(c, REASON_NEW_FRAME, now_ms);
    else if (session->ended && !v->told_ended)
        send_ended_notice(c);
    else if (session->latest && v->view_changed)
        dispatch(c, REASON_VIEW, now_ms);
    else if (session->latest && v->refresh_due_ms > 0.0 && now_ms >= v->refresh_due_ms)
        dispatch(c, REASON_REFRESH, now_ms);
}

void fc_viewer_start(struct fc_conversation *c, uint32_t subscribe_id, const fc_subscribe *sub, uint32_t auto_width,
                     uint32_t auto_height)
{
    fc_viewer *v = &c->viewer;
    memset(v, 0, sizeof *v);
    v->subscribe_id = subscribe_id;
    v->request = sub->request;
    v->auto_width = auto_width;
    v->auto_height = auto_height;
    /* Without memory for the stream every image is an IDR frame of its own (fc_h264_encode_single). */
    if (v->request.format == FC_FORMAT_H264)
        v->video = fc_h264_stream_create(v->request.quality);
    /* Missed frames count from the subscription: a frame already there is the first image, not a loss. */
    const fc_session *session = c->session;
    v->last_sequence = session->latest ? session->sequence - 1 : session->sequence;
    pump(c, fc_monotonic_ms());
}

void fc_viewer_view_changed(struct fc_conversation *c, double now_ms)
{
    if (!is_viewer(c))
        return;
    c->viewer.view_changed = true;
    c->viewer.view_changed_ms = now_ms;
    pump(c, now_ms);
}

void fc_viewer_keyframe_requested(struct fc_conversation *c, double now_ms)
{
    if (!is_viewer(c))
        return;
    c->viewer.keyframe_wanted = true;
    fc_viewer_view_changed(c, now_ms);
}

void fc_viewer_leave(struct fc_conversation *c, uint32_t request_id)
{
    c->viewer.leaving = true;
    c->viewer.end_request_id = request_id;
    pump(c, fc_monotonic_ms());
}

void fc_viewer_job_done(struct fc_conversation *c, const fc_render_job *job)
{
    /* An image of an earlier subscription (left while it was made, PROTOCOL.md 10.1) is dropped. */
    if (!is_viewer(c) || job->request_id != c->viewer.subscribe_id)
        return;
    c->viewer.queued = true;
    fc_error err;
    if (job->error.code != FC_OK) {
        c->viewer.keyframe_wanted = true;
        fc_conversation_send_error(c, job->request_id, &job->error);
        return;
    }
    if (fc_conversation_queue_message(c, &job->message, "the STREAM_IMAGE", &err) != FC_OK) {
        /* The image is lost like one a slow viewer misses; the ERROR says why.
         * An H.264 viewer lost an access unit its next frames would refer to. */
        c->viewer.keyframe_wanted = true;
        fc_conversation_send_error(c, job->request_id, &err);
        return;
    }
    c->viewer.queued_bytes = job->message.len;
}

size_t fc_viewer_backlog_allowance(const struct fc_conversation *c)
{
    enum { MIN_ALLOWANCE = 64 * 1024 };
    if (!is_viewer(c) || !c->viewer.queued)
        return SIZE_MAX;
    return c->viewer.queued_bytes > MIN_ALLOWANCE ? c->viewer.queued_bytes : MIN_ALLOWANCE;
}

void fc_viewer_drained(struct fc_conversation *c)
{
    if (!is_viewer(c) || !c->viewer.queued)
        return;
    c->viewer.queued = false;
    c->viewer.busy = false;
    pump(c, fc_monotonic_ms());
}

double fc_viewer_deadline_ms(const struct fc_conversation *c)
{
    if (!is_viewer(c) || c->viewer.busy || c->viewer.refresh_due_ms <= 0.0)
        return -1.0;
    return c->viewer.refresh_due_ms;
}

void fc_viewer_tick(struct fc_conversation *c, double now_ms)
{
    pump(c, now_ms);
}

void fc_viewer_detach(struct fc_conversation *c)
{
    fc_session *session = c->session;
    c->session = NULL;
    c->role = FC_ROLE_NONE;
    /* The encoder goes with the last reference: now, or when the image in flight is done. */
    fc_h264_stream_unref(c->viewer.video);
    memset(&c->viewer, 0, sizeof c->viewer);
    fc_session_remove_viewer(session, &c->member);
}

/* ---- What the named session tells its viewers ---- */

void fc_viewer_on_new_frame(struct fc_conversation *viewer)
{
    pump(viewer, fc_monotonic_ms());
}

void fc_viewer_on_session_ended(struct fc_conversation *viewer)
{
    pump(viewer, fc_monotonic_ms());
}

bool fc_viewer_in_ended_session(const struct fc_conversation *c)
{
    return is_viewer(c) && c->viewer.told_ended;
}
