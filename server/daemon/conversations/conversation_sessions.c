/* conversation_sessions.c — a client's named-session and packed-upload messages:
 * PUBLISH, SUBSCRIBE, SESSION_END, CHUNK, FRAME_PACKED and LIST_SESSIONS. */
#include "conversations/conversation_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conversations/conversation_memory.h"
#include "fc_error.h"
#include "monotonic.h"
#include "sessions/session.h"
#include "uploads/frame_pool.h"
#include "wire_session.h"

bool fc_conversation_is_session_message(uint16_t type)
{
    return fc_msg_capabilities(type) != 0;
}

static fc_conversation_verdict reply_error(fc_conversation *c, const fc_msg_header *h, const fc_error *err, fc_buf *out)
{
    return fc_conversation_reply_error(c->ctx, c->peer, h->request_id, err, FC_CONV_CONTINUE, out);
}

static fc_conversation_verdict reply_state(fc_conversation *c, const fc_msg_header *h, fc_buf *out)
{
    fc_session_info info;
    fc_error err;
    fc_session_describe(c->session, &info);
    if (fc_wire_write_session_state(out, h->request_id, &info, &err) != FC_OK) {
        fc_log_write(c->ctx->log, FC_LOG_ERROR, "%s: cannot queue SESSION_STATE: %s", c->peer, err.message);
        return FC_CONV_ABORT;
    }
    return FC_CONV_CONTINUE;
}

/* A viewer of a session that ended (and told it so) is out of it for a new
 * PUBLISH or SUBSCRIBE, which leave that session first (PROTOCOL.md 10.1). */
static fc_code check_no_role(fc_conversation *c, fc_error *err)
{
    if (fc_viewer_in_ended_session(c)) {
        fc_viewer_detach(c);
        /* Freed now if that was its last viewer, so its place counts for the new session. */
        fc_registry_collect(c->ctx->sessions);
    }
    if (c->role == FC_ROLE_NONE)
        return FC_OK;
    return fc_error_set(err, FC_ERR_BAD_STATE, "this connection already %s session '%s'",
                        c->role == FC_ROLE_PRODUCER ? "publishes to" : "watches", c->session->name);
}

void fc_conversation_detach(fc_conversation *c)
{
    fc_session *session = c->session;
    if (!session)
        return;
    if (c->role == FC_ROLE_VIEWER) {
        fc_viewer_detach(c);
        return;
    }
    c->session = NULL;
    c->role = FC_ROLE_NONE;
    /* After detaching: a producer's leaving may end the session, which then tells only the others. */
    fc_session_remove_producer(session, &c->member);
}

/* ---- What the named session tells this client (sessions/session_member.h) ---- */

static void on_new_frame(fc_session_member *viewer)
{
    fc_viewer_on_new_frame(fc_conversation_of_member(viewer));
}

static void on_session_ended(fc_session_member *viewer)
{
    fc_viewer_on_session_ended(fc_conversation_of_member(viewer));
}

/* The ERROR answers the chunk; the connection stays open. */
static void on_chunk_failed(fc_session_member *producer, uint32_t request_id, const fc_error *err)
{
    fc_conversation_send_error(fc_conversation_of_member(producer), request_id, err);
}

static const fc_session_member_ops member_ops = {
    .new_frame = on_new_frame,
    .session_ended = on_session_ended,
    .chunk_failed = on_chunk_failed,
};

/* ---- PUBLISH / SUBSCRIBE / SESSION_END ---- */

static fc_conversation_verdict handle_publish(fc_conversation *c, const fc_msg_header *h, const uint8_t *payload,
                                              fc_buf *out)
{
    char name[FC_SESSION_NAME_MAX + 1];
    fc_session *session;
    fc_error err;
    if (fc_wire_read_publish(payload, h->length, name, &err) != FC_OK || check_no_role(c, &err) != FC_OK ||
        fc_registry_open(c->ctx->sessions, name, &session, &err) != FC_OK)
        return reply_error(c, h, &err, out);
    c->member.ops = &member_ops;
    fc_session_add_producer(session);
    c->role = FC_ROLE_PRODUCER;
    c->session = session;
    fc_log_write(c->ctx->log, FC_LOG_INFO, "%s: publishes to session '%s'", c->peer, name);
    return reply_state(c, h, out);
}

static fc_conversation_verdict handle_subscribe(fc_conversation *c, const fc_msg_header *h, const uint8_t *payload,
                                                fc_buf *out)
{
    fc_subscribe sub;
    fc_session *session;
    fc_error err;
    if (fc_wire_read_subscribe(payload, h->length, &sub, &err) != FC_OK || check_no_role(c, &err) != FC_OK)
        return reply_error(c, h, &err, out);
    uint32_t width = sub.width ? sub.width : FC_DEFAULT_VIEW_WIDTH;
    uint32_t height = sub.height ? sub.height : FC_DEFAULT_VIEW_HEIGHT;
    c->member.ops = &member_ops;
    char what[64];
    snprintf(what, sizeof what, "an H.264 stream of %ux%u", (unsigned)width, (unsigned)height);
    uint64_t encoder = fc_memory_of_video(sub.request.format, c->has_camera ? c->camera.width : width,
                                          c->has_camera ? c->camera.height : height);
    if (fc_conversation_check_image_limit(&c->ctx->welcome.limits, width, height, &err) != FC_OK ||
        fc_conversation_memory_admit(c, 0, encoder, what, &err) != FC_OK ||
        fc_registry_open(c->ctx->sessions, sub.name, &session, &err) != FC_OK ||
        fc_session_add_viewer(session, &c->member, &err) != FC_OK)
        return reply_error(c, h, &err, out);
    c->role = FC_ROLE_VIEWER;
    c->session = session;
    fc_log_write(c->ctx->log, FC_LOG_INFO, "%s: watches session '%s'", c->peer, sub.name);
    /* The acknowledgement goes first: the first image may follow at once. */
    fc_conversation_verdict verdict = reply_state(c, h, out);
    if (verdict == FC_CONV_CONTINUE)
        fc_viewer_start(c, h->request_id, &sub, width, height);
    return verdict;
}

static fc_conversation_verdict handle_session_end(fc_conversation *c, const fc_msg_header *h, const uint8_t *payload,
                                                  fc_buf *out)
{
    fc_error err;
    if (fc_wire_read_session_leave(payload, h->length, &err) != FC_OK)
        return reply_error(c, h, &err, out);
    if (c->role == FC_ROLE_NONE) {
        fc_error_set(&err, FC_ERR_BAD_STATE, "SESSION_END outside a session");
        return reply_error(c, h, &err, out);
    }
    if (c->role == FC_ROLE_VIEWER && c->viewer.leaving) {
        fc_error_set(&err, FC_ERR_BAD_STATE, "SESSION_END was sent already");
        return reply_error(c, h, &err, out);
    }
    if (c->role == FC_ROLE_VIEWER) {
        fc_viewer_leave(c, h->request_id);
        return FC_CONV_CONTINUE;
    }
    char name[FC_SESSION_NAME_MAX + 1];
    memcpy(name, c->session->name, sizeof name);
    fc_conversation_detach(c);
    fc_log_write(c->ctx->log, FC_LOG_INFO, "%s: stopped publishing to session '%s'", c->peer, name);
    if (fc_wire_write_session_end(out, h->request_id, name, &err) != FC_OK)
        return FC_CONV_ABORT;
    return FC_CONV_CONTINUE;
}

/* ---- Frames: FRAME_PACKED and CHUNK ---- */

static fc_conversation_verdict handle_frame_packed(fc_conversation *c, const fc_msg_header *h, fc_payload *payload,
                                                   double received_ms, fc_buf *out)
{
    fc_frame_view view = {0};
    fc_error err;
    double start = fc_monotonic_ms();
    fc_block_source blocks = fc_frame_pool_source(c->ctx->frames);
    fc_code code = fc_wire_view_frame_packed(payload->bytes, h->length, fc_pack_allowed(c->capabilities),
                                             c->ctx->welcome.limits.max_particles, &blocks, &view, &err);
    if (code == FC_OK)
        code = fc_conversation_take_frame(c, &view, payload, received_ms, fc_monotonic_ms() - start, &err);
    return code == FC_OK ? FC_CONV_CONTINUE : reply_error(c, h, &err, out);
}

/* Publishes a frame the chunks completed, unless a newer one is out already
 * (chunks of two frames can complete out of order; viewers only go forward). */
static fc_code publish_assembled(fc_conversation *c, fc_assembled_frame *done, fc_error *err)
{
    fc_session *session = c->session;
    if (session->latest && done->frame_number <= session->latest->number) {
        fc_log_write(c->ctx->log, FC_LOG_DEBUG, "%s: frame %llu completed after frame %llu: dropped", c->peer,
                     (unsigned long long)done->frame_number, (unsigned long long)session->latest->number);
        fc_frame_pool_give_view(c->ctx->frames, &done->frame);
        return FC_OK;
    }
    fc_shared_frame *shared;
    fc_code code =
        fc_shared_frame_create(&done->frame, c->ctx->frames, ++c->ctx->last_frame_id, session->foam, &shared, err);
    if (code != FC_OK)
        return code;
    shared->number = done->frame_number;
    shared->ready_ms = fc_monotonic_ms();
    shared->receive_ms = done->receive_ms;
    shared->decode_ms = done->decode_ms;
    fc_session_publish(session, shared);
    return FC_OK;
}

/* The frames being assembled hold every chunk until their last one arrives. */
static fc_code admit_chunk(const fc_conversation *c, const fc_chunk *chunk, fc_error *err)
{
    char what[96];
    snprintf(what, sizeof what, "chunk %u of frame %llu (%llu particles)", chunk->header.index,
             (unsigned long long)chunk->header.frame_number, (unsigned long long)chunk->part.frame.count);
    return fc_conversation_memory_admit(c, 0, fc_memory_of_frame(&chunk->part.frame), what, err);
}

static fc_conversation_verdict handle_chunk(fc_conversation *c, const fc_msg_header *h, fc_payload *payload,
                                            double received_ms, fc_buf *out)
{
    fc_error err;
    if (c->role != FC_ROLE_PRODUCER) {
        fc_error_set(&err, FC_ERR_BAD_STATE, "CHUNK needs PUBLISH first");
        return reply_error(c, h, &err, out);
    }
    fc_frame_pool *pool = c->ctx->frames;
    fc_block_source blocks = fc_frame_pool_source(pool);
    fc_chunk chunk = {0};
    double start = fc_monotonic_ms();
    fc_code code = fc_wire_view_chunk(payload->bytes, h->length, fc_pack_allowed(c->capabilities),
                                      c->ctx->welcome.limits.max_particles, &blocks, &chunk.header, &chunk.part, &err);
    if (code == FC_OK)
        code = fc_conversation_keep_payload(c, &chunk.part, payload, &err);
    if (code == FC_OK)
        code = admit_chunk(c, &chunk, &err);
    if (code != FC_OK) {
        fc_frame_pool_give_view(pool, &chunk.part);
        return reply_error(c, h, &err, out);
    }
    double now = fc_monotonic_ms();
    chunk.origin = (fc_chunk_origin){&c->member, h->request_id};
    chunk.first_byte_ms = c->message_started_ms;
    chunk.received_ms = received_ms;
    chunk.decode_ms = (float)(now - start);
    bool complete = false;
    fc_assembled_frame done = {0};
    code = fc_chunk_assembly_add(&c->session->chunks, &chunk, c->ctx->welcome.limits.max_particles, now,
                                 c->ctx->chunk_timeout_ms, &complete, &done, &err);
    fc_frame_pool_give_view(pool, &chunk.part);
    if (code == FC_OK && complete)
        code = publish_assembled(c, &done, &err);
    return code == FC_OK ? FC_CONV_CONTINUE : reply_error(c, h, &err, out);
}

/* ---- LIST_SESSIONS ---- */

static fc_conversation_verdict handle_list_sessions(fc_conversation *c, const fc_msg_header *h, const uint8_t *payload,
                                                    fc_buf *out)
{
    fc_session_info *list = NULL;
    uint32_t count = 0;
    fc_error err;
    fc_code code = fc_wire_read_list_sessions(payload, h->length, &err);
    if (code == FC_OK)
        code = fc_registry_list(c->ctx->sessions, &list, &count, &err);
    if (code == FC_OK)
        code = fc_wire_write_session_list(out, h->request_id, list, count, &err);
    free(list);
    return code == FC_OK ? FC_CONV_CONTINUE : reply_error(c, h, &err, out);
}

/* ---- Dispatch ---- */

fc_conversation_verdict fc_conversation_handle_session_message(fc_conversation *c, fc_daemon_context *ctx,
                                                               const fc_msg_header *h, fc_payload *message,
                                                               double received_ms, fc_buf *out)
{
    const uint8_t *payload = message->bytes;
    (void)ctx;
    fc_error err;
    /* A type is undefined on connections that were granted none of the capabilities it needs. */
    if (!(c->capabilities & fc_msg_capabilities(h->type))) {
        fc_error_set(&err, FC_ERR_UNKNOWN_TYPE, "%s (type %u) needs a capability this connection did not negotiate",
                     fc_msg_name(h->type), (unsigned)h->type);
        return reply_error(c, h, &err, out);
    }
    switch (h->type) {
    case FC_MSG_PUBLISH: return handle_publish(c, h, payload, out);
    case FC_MSG_SUBSCRIBE: return handle_subscribe(c, h, payload, out);
    case FC_MSG_SESSION_END: return handle_session_end(c, h, payload, out);
    case FC_MSG_CHUNK: return handle_chunk(c, h, message, received_ms, out);
    case FC_MSG_FRAME_PACKED: return handle_frame_packed(c, h, message, received_ms, out);
    case FC_MSG_LIST_SESSIONS: return handle_list_sessions(c, h, payload, out);
    default:
        fc_error_set(&err, FC_ERR_BAD_STATE, "%s is sent by servers, not clients", fc_msg_name(h->type));
        return reply_error(c, h, &err, out);
    }
}
