/* viewer.c — see viewer.h. */
#include "clients/viewer.h"

#include <string.h>

#include "clients/session_internal.h"
#include "fc_error.h"
#include "monotonic.h"
#include "sessions/session_events.h"
#include "sessions/stream_session.h"

typedef enum image_reason {
    REASON_NEW_FRAME = 0,    /* the session published a frame this viewer has not seen */
    REASON_VIEW,             /* the viewer's camera or settings changed */
    REASON_REFRESH           /* lossless copy of a frame shown lossy */
} image_reason;

static bool is_viewer(const struct fc_session *s)
{
    return s->role == FC_ROLE_VIEWER;
}

static fc_render_order order_for(const struct fc_session *s, image_reason reason, double now_ms)
{
    const fc_viewer *v = &s->viewer;
    const fc_stream_session *stream = s->stream;
    fc_render_order order = {0};
    order.kind = FC_JOB_STREAM;
    order.request_id = v->subscribe_id;
    order.request = v->request;
    order.auto_width = v->auto_width;
    order.auto_height = v->auto_height;
    order.tag.frame_number = stream->latest->number;
    order.tag.sequence = stream->sequence;
    if (reason == REASON_NEW_FRAME) {
        uint64_t missed = stream->sequence - v->last_sequence - 1;
        order.tag.missed = missed > UINT32_MAX ? UINT32_MAX : (uint32_t)missed;
        order.received_ms = stream->latest->ready_ms;
    } else if (reason == REASON_VIEW) {
        order.tag.flags = FC_STREAM_VIEW;
        order.received_ms = v->view_changed_ms;
    } else {
        order.tag.flags = FC_STREAM_REFRESH;
        order.request.format = FC_FORMAT_PNG;
        order.received_ms = now_ms;
    }
    return order;
}

static void dispatch(struct fc_session *s, image_reason reason, double now_ms)
{
    fc_viewer *v = &s->viewer;
    fc_render_order order = order_for(s, reason, now_ms);
    fc_error err;
    if (fc_session_submit_render(s, s->stream->latest, &order, &err) != FC_OK) {
        fc_session_send_error(s, v->subscribe_id, &err);
        return;
    }
    v->busy = true;
    v->view_changed = false;
    v->last_sequence = s->stream->sequence;
    double refresh_ms = s->ctx->refresh_ms;
    bool lossy = order.request.format == FC_FORMAT_JPEG;
    v->refresh_due_ms = lossy && refresh_ms > 0.0 ? now_ms + refresh_ms : 0.0;
}

static void send_end(struct fc_session *s)
{
    fc_error err;
    fc_stream_session *stream = s->stream;
    if (fc_wire_write_session_end(s->out, s->viewer.end_request_id, stream->name, &err) != FC_OK)
        fc_log_write(s->ctx->log, FC_LOG_ERROR, "%s: cannot queue SESSION_END: %s", s->peer, err.message);
    fc_log_write(s->ctx->log, FC_LOG_INFO, "%s: left session '%s' as a viewer", s->peer, stream->name);
    fc_session_leave_stream(s);
}

/* Starts the next image this viewer is due, or ends its subscription. */
static void pump(struct fc_session *s, double now_ms)
{
    fc_viewer *v = &s->viewer;
    if (!is_viewer(s) || v->busy)
        return;
    const fc_stream_session *stream = s->stream;
    bool new_frame = stream->latest && stream->sequence > v->last_sequence;
    if (v->ending && !(v->deliver_last && new_frame))
        send_end(s);
    else if (new_frame)
        dispatch(s, REASON_NEW_FRAME, now_ms);
    else if (stream->latest && v->view_changed && !v->ending)
        dispatch(s, REASON_VIEW, now_ms);
    else if (stream->latest && v->refresh_due_ms > 0.0 && now_ms >= v->refresh_due_ms && !v->ending)
        dispatch(s, REASON_REFRESH, now_ms);
}

void fc_viewer_start(struct fc_session *s, uint32_t subscribe_id, const fc_subscribe *sub, uint32_t auto_width,
                     uint32_t auto_height)
{
    fc_viewer *v = &s->viewer;
    memset(v, 0, sizeof *v);
    v->subscribe_id = subscribe_id;
    v->request = sub->request;
    v->auto_width = auto_width;
    v->auto_height = auto_height;
    /* Missed frames count from the subscription: a frame already there is the first image, not a loss. */
    const fc_stream_session *stream = s->stream;
    v->last_sequence = stream->latest ? stream->sequence - 1 : stream->sequence;
    pump(s, fc_monotonic_ms());
}

void fc_viewer_view_changed(struct fc_session *s, double now_ms)
{
    if (!is_viewer(s))
        return;
    s->viewer.view_changed = true;
    s->viewer.view_changed_ms = now_ms;
    pump(s, now_ms);
}

void fc_viewer_leave(struct fc_session *s, uint32_t request_id)
{
    s->viewer.ending = true;
    s->viewer.deliver_last = false;
    s->viewer.end_request_id = request_id;
    pump(s, fc_monotonic_ms());
}

void fc_viewer_job_done(struct fc_session *s, const fc_render_job *job)
{
    if (!is_viewer(s))
        return;
    s->viewer.queued = true;
    fc_error err;
    if (job->error.code != FC_OK) {
        fc_session_send_error(s, job->request_id, &job->error);
        return;
    }
    if (fc_session_queue_message(s, &job->message, "the STREAM_IMAGE", &err) != FC_OK) {
        /* The image is lost like one a slow viewer misses; the ERROR says why. */
        fc_session_send_error(s, job->request_id, &err);
        return;
    }
    s->viewer.queued_bytes = job->message.len;
}

size_t fc_viewer_backlog_allowance(const struct fc_session *s)
{
    enum { MIN_ALLOWANCE = 64 * 1024 };
    if (!is_viewer(s) || !s->viewer.queued)
        return SIZE_MAX;
    return s->viewer.queued_bytes > MIN_ALLOWANCE ? s->viewer.queued_bytes : MIN_ALLOWANCE;
}

void fc_viewer_drained(struct fc_session *s)
{
    if (!is_viewer(s) || !s->viewer.queued)
        return;
    s->viewer.queued = false;
    s->viewer.busy = false;
    pump(s, fc_monotonic_ms());
}

double fc_viewer_deadline_ms(const struct fc_session *s)
{
    if (!is_viewer(s) || s->viewer.busy || s->viewer.refresh_due_ms <= 0.0)
        return -1.0;
    return s->viewer.refresh_due_ms;
}

void fc_viewer_tick(struct fc_session *s, double now_ms)
{
    pump(s, now_ms);
}

/* ---- What the named session tells its viewers ---- */

void fc_session_on_new_frame(struct fc_session *viewer)
{
    pump(viewer, fc_monotonic_ms());
}

void fc_session_on_stream_ended(struct fc_session *viewer)
{
    fc_viewer *v = &viewer->viewer;
    if (v->ending)
        return;
    v->ending = true;
    v->deliver_last = true;
    v->end_request_id = v->subscribe_id;
    pump(viewer, fc_monotonic_ms());
}
