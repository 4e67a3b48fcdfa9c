/* session_stream.c — the session and packed-upload messages of a connection:
 * PUBLISH, SUBSCRIBE, SESSION_END, CHUNK, FRAME_PACKED and LIST_SESSIONS. */
#include "clients/session_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clients/session_memory.h"
#include "fc_error.h"
#include "monotonic.h"
#include "sessions/session_events.h"
#include "sessions/stream_session.h"
#include "uploads/frame_pool.h"
#include "wire_session.h"

bool fc_session_is_stream_message(uint16_t type)
{
    return fc_wire_session_type_name(type) != NULL;
}

static fc_session_verdict reply_error(fc_session *s, const fc_msg_header *h, const fc_error *err, fc_buf *out)
{
    return fc_session_reply_error(s->ctx, s->peer, h->request_id, err, FC_SESSION_CONTINUE, out);
}

static fc_session_verdict reply_state(fc_session *s, const fc_msg_header *h, fc_buf *out)
{
    fc_session_info info;
    fc_error err;
    fc_stream_session_describe(s->stream, &info);
    if (fc_wire_write_session_state(out, h->request_id, &info, &err) != FC_OK) {
        fc_log_write(s->ctx->log, FC_LOG_ERROR, "%s: cannot queue SESSION_STATE: %s", s->peer, err.message);
        return FC_SESSION_ABORT;
    }
    return FC_SESSION_CONTINUE;
}

static fc_code check_no_role(const fc_session *s, fc_error *err)
{
    if (s->role == FC_ROLE_NONE)
        return FC_OK;
    return fc_error_set(err, FC_ERR_BAD_STATE, "this connection already %s session '%s'",
                        s->role == FC_ROLE_PRODUCER ? "publishes to" : "watches", s->stream->name);
}

void fc_session_leave_stream(fc_session *s)
{
    fc_stream_session *stream = s->stream;
    if (!stream)
        return;
    fc_session_role role = s->role;
    s->stream = NULL;
    s->role = FC_ROLE_NONE;
    memset(&s->viewer, 0, sizeof s->viewer);
    /* After detaching: a producer's leaving may end the session, which then tells only the others. */
    if (role == FC_ROLE_PRODUCER)
        fc_stream_session_remove_producer(stream, s);
    else
        fc_stream_session_remove_viewer(stream, s);
}

/* ---- PUBLISH / SUBSCRIBE / SESSION_END ---- */

static fc_session_verdict handle_publish(fc_session *s, const fc_msg_header *h, const uint8_t *payload,
                                         fc_buf *out)
{
    char name[FC_SESSION_NAME_MAX + 1];
    fc_stream_session *stream;
    fc_error err;
    if (fc_wire_read_publish(payload, h->length, name, &err) != FC_OK || check_no_role(s, &err) != FC_OK ||
        fc_registry_open(s->ctx->sessions, name, &stream, &err) != FC_OK)
        return reply_error(s, h, &err, out);
    fc_stream_session_add_producer(stream);
    s->role = FC_ROLE_PRODUCER;
    s->stream = stream;
    fc_log_write(s->ctx->log, FC_LOG_INFO, "%s: publishes to session '%s'", s->peer, name);
    return reply_state(s, h, out);
}

static fc_session_verdict handle_subscribe(fc_session *s, const fc_msg_header *h, const uint8_t *payload,
                                           fc_buf *out)
{
    fc_subscribe sub;
    fc_stream_session *stream;
    fc_error err;
    if (fc_wire_read_subscribe(payload, h->length, &sub, &err) != FC_OK || check_no_role(s, &err) != FC_OK)
        return reply_error(s, h, &err, out);
    uint32_t width = sub.width ? sub.width : FC_DEFAULT_VIEW_WIDTH;
    uint32_t height = sub.height ? sub.height : FC_DEFAULT_VIEW_HEIGHT;
    if (fc_session_check_image_limit(&s->ctx->welcome.limits, width, height, &err) != FC_OK ||
        fc_registry_open(s->ctx->sessions, sub.name, &stream, &err) != FC_OK ||
        fc_stream_session_add_viewer(stream, s, &err) != FC_OK)
        return reply_error(s, h, &err, out);
    s->role = FC_ROLE_VIEWER;
    s->stream = stream;
    fc_log_write(s->ctx->log, FC_LOG_INFO, "%s: watches session '%s'", s->peer, sub.name);
    /* The acknowledgement goes first: the first image may follow at once. */
    fc_session_verdict verdict = reply_state(s, h, out);
    if (verdict == FC_SESSION_CONTINUE)
        fc_viewer_start(s, h->request_id, &sub, width, height);
    return verdict;
}

static fc_session_verdict handle_session_end(fc_session *s, const fc_msg_header *h, const uint8_t *payload,
                                             fc_buf *out)
{
    fc_error err;
    if (fc_wire_read_session_leave(payload, h->length, &err) != FC_OK)
        return reply_error(s, h, &err, out);
    if (s->role == FC_ROLE_NONE) {
        fc_error_set(&err, FC_ERR_BAD_STATE, "SESSION_END outside a session");
        return reply_error(s, h, &err, out);
    }
    if (s->role == FC_ROLE_VIEWER && s->viewer.ending && !s->viewer.deliver_last) {
        fc_error_set(&err, FC_ERR_BAD_STATE, "SESSION_END was sent already");
        return reply_error(s, h, &err, out);
    }
    if (s->role == FC_ROLE_VIEWER) {
        fc_viewer_leave(s, h->request_id);
        return FC_SESSION_CONTINUE;
    }
    char name[FC_SESSION_NAME_MAX + 1];
    memcpy(name, s->stream->name, sizeof name);
    fc_session_leave_stream(s);
    fc_log_write(s->ctx->log, FC_LOG_INFO, "%s: stopped publishing to session '%s'", s->peer, name);
    if (fc_wire_write_session_end(out, h->request_id, name, &err) != FC_OK)
        return FC_SESSION_ABORT;
    return FC_SESSION_CONTINUE;
}

/* ---- Frames: FRAME_PACKED and CHUNK ---- */

static fc_session_verdict handle_frame_packed(fc_session *s, const fc_msg_header *h, fc_payload *payload,
                                              double received_ms, fc_buf *out)
{
    fc_frame_view view = {0};
    fc_error err;
    double start = fc_monotonic_ms();
    fc_block_source blocks = fc_frame_pool_source(s->ctx->frames);
    fc_code code = fc_wire_view_frame_packed(payload->bytes, h->length, fc_pack_allowed(s->capabilities),
                                             s->ctx->welcome.limits.max_particles, &blocks, &view, &err);
    if (code == FC_OK)
        code = fc_session_take_frame(s, &view, payload, received_ms, fc_monotonic_ms() - start, &err);
    return code == FC_OK ? FC_SESSION_CONTINUE : reply_error(s, h, &err, out);
}

/* Publishes a frame the chunks completed, unless a newer one is out already
 * (chunks of two frames can complete out of order; viewers only go forward). */
static fc_code publish_assembled(fc_session *s, fc_assembled_frame *done, fc_error *err)
{
    fc_stream_session *stream = s->stream;
    if (stream->latest && done->frame_number <= stream->latest->number) {
        fc_log_write(s->ctx->log, FC_LOG_DEBUG, "%s: frame %llu completed after frame %llu: dropped", s->peer,
                     (unsigned long long)done->frame_number, (unsigned long long)stream->latest->number);
        fc_frame_pool_give_view(s->ctx->frames, &done->frame);
        return FC_OK;
    }
    fc_shared_frame *shared;
    fc_code code =
        fc_shared_frame_create(&done->frame, s->ctx->frames, ++s->ctx->last_frame_id, stream->foam, &shared, err);
    if (code != FC_OK)
        return code;
    shared->number = done->frame_number;
    shared->ready_ms = fc_monotonic_ms();
    shared->receive_ms = done->receive_ms;
    shared->decode_ms = done->decode_ms;
    fc_stream_session_publish(stream, shared);
    return FC_OK;
}

/* The frames being assembled hold every chunk until their last one arrives. */
static fc_code admit_chunk(const fc_session *s, const fc_chunk *chunk, fc_error *err)
{
    char what[96];
    snprintf(what, sizeof what, "chunk %u of frame %llu (%llu particles)", chunk->header.index,
             (unsigned long long)chunk->header.frame_number, (unsigned long long)chunk->part.frame.count);
    return fc_session_memory_admit(s, 0, fc_memory_of_frame(&chunk->part.frame), what, err);
}

static fc_session_verdict handle_chunk(fc_session *s, const fc_msg_header *h, fc_payload *payload,
                                       double received_ms, fc_buf *out)
{
    fc_error err;
    if (s->role != FC_ROLE_PRODUCER) {
        fc_error_set(&err, FC_ERR_BAD_STATE, "CHUNK needs PUBLISH first");
        return reply_error(s, h, &err, out);
    }
    fc_frame_pool *pool = s->ctx->frames;
    fc_block_source blocks = fc_frame_pool_source(pool);
    fc_chunk chunk = {0};
    double start = fc_monotonic_ms();
    fc_code code = fc_wire_view_chunk(payload->bytes, h->length, fc_pack_allowed(s->capabilities),
                                      s->ctx->welcome.limits.max_particles, &blocks, &chunk.header, &chunk.part, &err);
    if (code == FC_OK)
        code = fc_session_keep_payload(s, &chunk.part, payload, &err);
    if (code == FC_OK)
        code = admit_chunk(s, &chunk, &err);
    if (code != FC_OK) {
        fc_frame_pool_give_view(pool, &chunk.part);
        return reply_error(s, h, &err, out);
    }
    double now = fc_monotonic_ms();
    chunk.origin = (fc_chunk_origin){s, h->request_id};
    chunk.first_byte_ms = s->message_started_ms;
    chunk.received_ms = received_ms;
    chunk.decode_ms = (float)(now - start);
    bool complete = false;
    fc_assembled_frame done = {0};
    code = fc_chunk_assembly_add(&s->stream->chunks, &chunk, s->ctx->welcome.limits.max_particles, now,
                                 s->ctx->chunk_timeout_ms, &complete, &done, &err);
    fc_frame_pool_give_view(pool, &chunk.part);
    if (code == FC_OK && complete)
        code = publish_assembled(s, &done, &err);
    return code == FC_OK ? FC_SESSION_CONTINUE : reply_error(s, h, &err, out);
}

/* ---- LIST_SESSIONS ---- */

static fc_session_verdict handle_list_sessions(fc_session *s, const fc_msg_header *h, const uint8_t *payload,
                                               fc_buf *out)
{
    fc_session_info *list = NULL;
    uint32_t count = 0;
    fc_error err;
    fc_code code = fc_wire_read_list_sessions(payload, h->length, &err);
    if (code == FC_OK)
        code = fc_registry_list(s->ctx->sessions, &list, &count, &err);
    if (code == FC_OK)
        code = fc_wire_write_session_list(out, h->request_id, list, count, &err);
    free(list);
    return code == FC_OK ? FC_SESSION_CONTINUE : reply_error(s, h, &err, out);
}

/* ---- Dispatch ---- */

/* The capabilities a message type needs: it is undefined on connections that did not get them. */
static uint32_t required_capabilities(uint16_t type)
{
    return type == FC_MSG_FRAME_PACKED ? (uint32_t)(FC_CAP_ZSTD | FC_CAP_QUANTIZE16) : (uint32_t)FC_CAP_SESSIONS;
}

fc_session_verdict fc_session_handle_stream(fc_session *s, fc_daemon_context *ctx, const fc_msg_header *h,
                                            fc_payload *message, double received_ms, fc_buf *out)
{
    const uint8_t *payload = message->bytes;
    (void)ctx;
    fc_error err;
    if (!(s->capabilities & required_capabilities(h->type))) {
        fc_error_set(&err, FC_ERR_UNKNOWN_TYPE, "%s (type %u) needs a capability this connection did not negotiate",
                     fc_wire_session_type_name(h->type), (unsigned)h->type);
        return reply_error(s, h, &err, out);
    }
    switch (h->type) {
    case FC_MSG_PUBLISH: return handle_publish(s, h, payload, out);
    case FC_MSG_SUBSCRIBE: return handle_subscribe(s, h, payload, out);
    case FC_MSG_SESSION_END: return handle_session_end(s, h, payload, out);
    case FC_MSG_CHUNK: return handle_chunk(s, h, message, received_ms, out);
    case FC_MSG_FRAME_PACKED: return handle_frame_packed(s, h, message, received_ms, out);
    case FC_MSG_LIST_SESSIONS: return handle_list_sessions(s, h, payload, out);
    default:
        fc_error_set(&err, FC_ERR_BAD_STATE, "%s is sent by servers, not clients", fc_wire_session_type_name(h->type));
        return reply_error(s, h, &err, out);
    }
}

void fc_session_on_chunk_failed(const fc_chunk_origin *origin, const fc_error *err, void *data)
{
    (void)data;
    fc_session_send_error(origin->session, origin->request_id, err);
}
