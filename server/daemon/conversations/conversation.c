/* conversation.c — one connection's protocol state: the handshake, the dispatch of
 * its messages, and what its connection reports (render results, output sent,
 * timers). */
#include "conversations/conversation.h"

#include <stdio.h>
#include <string.h>

#include "conversations/conversation_internal.h"
#include "conversations/conversation_memory.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "monotonic.h"
#include "wire_mesh.h"
#include "wire_session.h"
#include "wire_surface.h"

void fc_conversation_init(fc_conversation *c, const char *peer, fc_daemon_context *ctx, uint64_t connection_id,
                          fc_buf *out)
{
    memset(c, 0, sizeof *c);
    c->state = FC_CONV_AWAIT_HELLO;
    c->peer = peer;
    c->ctx = ctx;
    c->connection_id = connection_id;
    c->out = out;
    fc_settings_default(&c->settings);
}

void fc_conversation_free(fc_conversation *c)
{
    fc_conversation_detach(c);
    fc_shared_frame_unref(c->frame);
    c->frame = NULL;
    fc_foam_track_unref(c->foam);
    c->foam = NULL;
    fc_scene_uploads_free(&c->scene);
    fc_mesh_set_free(&c->meshes);
}

/* A type defined for every connection, whatever it negotiated: before HELLO
 * nothing is negotiated, so the types that need a capability are undefined. */
static bool is_defined_without_capabilities(uint16_t type)
{
    return fc_msg_name(type) != NULL && fc_msg_capabilities(type) == 0;
}

/* Shorthand for the handlers: answer the message `h` with err. */
static fc_conversation_verdict reply_error(const fc_conversation *c, const fc_daemon_context *ctx,
                                           const fc_msg_header *h, const fc_error *err, fc_conversation_verdict then,
                                           fc_buf *out)
{
    return fc_conversation_reply_error(ctx, c->peer, h->request_id, err, then, out);
}

static fc_conversation_verdict handle_hello(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                            const uint8_t *payload, fc_buf *out)
{
    fc_hello hello;
    fc_error err;
    if (fc_wire_read_hello(payload, h->length, &hello, &err) != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CLOSE, out);
    if (hello.version_min > FC_PROTOCOL_VERSION || hello.version_max < FC_PROTOCOL_VERSION) {
        fc_error_set(&err, FC_ERR_VERSION, "client speaks protocol versions %u..%u, this server only %u",
                     (unsigned)hello.version_min, (unsigned)hello.version_max, FC_PROTOCOL_VERSION);
        return reply_error(c, ctx, h, &err, FC_CONV_CLOSE, out);
    }
    /* Capabilities are granted as requested, as far as this server has them. */
    fc_welcome welcome = ctx->welcome;
    welcome.capabilities = hello.capabilities & FC_CAPS_ALL;
    if (fc_wire_write_welcome(out, h->request_id, &welcome, &err) != FC_OK) {
        fc_log_write(ctx->log, FC_LOG_ERROR, "%s: cannot queue WELCOME: %s", c->peer, err.message);
        return FC_CONV_ABORT;
    }
    c->state = FC_CONV_READY;
    c->capabilities = welcome.capabilities;
    fc_log_write(ctx->log, FC_LOG_INFO, "%s: HELLO from '%s' (capabilities 0x%x)", c->peer, hello.client_name,
                 (unsigned)welcome.capabilities);
    return FC_CONV_CONTINUE;
}

/* A new frame replaces the old one only once it decoded completely; on a
 * producer it is published to the named session. */
static fc_conversation_verdict handle_frame(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                            fc_payload *payload, double received_ms, fc_buf *out)
{
    fc_frame_view view = {0};
    fc_error err;
    double start = fc_monotonic_ms();
    /* Decoded in place: the payload's block becomes the frame's. */
    fc_code code = fc_wire_view_frame(payload->bytes, h->length, ctx->welcome.limits.max_particles, &view.frame, &err);
    if (code == FC_OK) {
        fc_log_write(ctx->log, FC_LOG_DEBUG, "%s: FRAME of %llu particles", c->peer,
                     (unsigned long long)view.frame.count);
        code = fc_conversation_take_frame(c, &view, payload, received_ms, fc_monotonic_ms() - start, &err);
    }
    if (code != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    return FC_CONV_CONTINUE;
}

/* An H.264 viewer's encoder grows with its images: a CAMERA of another size must fit. */
static fc_code admit_video_size(const fc_conversation *c, const fc_camera *camera, fc_error *err)
{
    if (c->role != FC_ROLE_VIEWER || c->viewer.request.format != FC_FORMAT_H264)
        return FC_OK;
    fc_image_format format = c->viewer.request.format;
    uint32_t width = c->has_camera ? c->camera.width : c->viewer.auto_width;
    uint32_t height = c->has_camera ? c->camera.height : c->viewer.auto_height;
    char what[64];
    snprintf(what, sizeof what, "an H.264 stream of %ux%u", (unsigned)camera->width, (unsigned)camera->height);
    return fc_conversation_memory_admit(c, fc_memory_of_video(format, width, height),
                                        fc_memory_of_video(format, camera->width, camera->height), what, err);
}

static fc_conversation_verdict handle_camera(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                             const uint8_t *payload, fc_buf *out)
{
    fc_camera camera;
    fc_error err;
    if (fc_wire_read_camera(payload, h->length, &camera, &err) != FC_OK ||
        fc_conversation_check_image_limit(&ctx->welcome.limits, camera.width, camera.height, &err) != FC_OK ||
        admit_video_size(c, &camera, &err) != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    c->camera = camera;
    c->has_camera = true;
    fc_viewer_view_changed(c, fc_monotonic_ms());
    return FC_CONV_CONTINUE;
}

/* The payload of a SETTINGS without entries: its count alone. */
enum { SETTINGS_EMPTY_SIZE = 4 };

/* Entries merge into the current settings; the codec leaves them untouched on any error. */
static fc_conversation_verdict handle_settings(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                               const uint8_t *payload, fc_buf *out)
{
    fc_error err;
    if (fc_wire_read_settings(payload, h->length, &c->settings, &err) != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    /* An empty SETTINGS changes nothing: a viewer sends it to ask for a key frame (PROTOCOL.md 10.7). */
    if (h->length == SETTINGS_EMPTY_SIZE)
        fc_viewer_keyframe_requested(c, fc_monotonic_ms());
    else
        fc_viewer_view_changed(c, fc_monotonic_ms());
    return FC_CONV_CONTINUE;
}

/* BACKGROUND / ENVIRONMENT: decoded now, so a bad image is answered at once;
 * renders queued before keep the images they were submitted with. The image
 * it replaces is given up only once the new one is known to fit. */
static fc_conversation_verdict handle_scene_image(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                                  const uint8_t *payload, fc_buf *out)
{
    fc_error err;
    bool background = h->type == FC_MSG_BACKGROUND;
    fc_scene_part **slot = background ? &c->scene.background : &c->scene.environment;
    fc_scene_part *part;
    fc_code code = background ? fc_scene_part_decode_background(payload, h->length, &part, &err)
                              : fc_scene_part_decode_environment(payload, h->length, &part, &err);
    if (code == FC_OK)
        code = fc_conversation_memory_admit(c, fc_memory_of_scene_part(*slot), fc_memory_of_scene_part(part),
                                            background ? "BACKGROUND" : "ENVIRONMENT", &err);
    if (code != FC_OK) {
        fc_scene_part_unref(part);
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    }
    fc_scene_uploads_replace(slot, part);
    fc_viewer_view_changed(c, fc_monotonic_ms());
    return FC_CONV_CONTINUE;
}

/* The meshes a MESH or MESH_TRANSFORM changes: a producer's are its
 * session's, shown by every viewer; anyone else's are its own. */
static fc_mesh_set *mesh_set_of(fc_conversation *c)
{
    return c->role == FC_ROLE_PRODUCER ? &c->session->meshes : &c->meshes;
}

/* MESH: decoded and checked now, so a bad mesh is answered at once; the mesh
 * it replaces is given up only once the new one is known to fit. */
static fc_conversation_verdict handle_mesh(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                           const uint8_t *payload, fc_buf *out)
{
    fc_error err;
    fc_mesh_set *set = mesh_set_of(c);
    fc_mesh_geometry *g = NULL;
    uint32_t id = 0;
    fc_code code = fc_mesh_geometry_decode(payload, h->length, &g, &id, &err);
    int at = code == FC_OK ? fc_mesh_set_find(set, id) : -1;
    if (code == FC_OK && g)
        code = fc_mesh_set_check_room(set, id, &err);
    if (code == FC_OK && g) {
        char what[64];
        snprintf(what, sizeof what, "MESH %u", (unsigned)id);
        code = fc_conversation_memory_admit(c, at >= 0 ? fc_mesh_geometry_bytes(set->entries[at].geometry) : 0,
                                            fc_mesh_geometry_bytes(g), what, &err);
    }
    if (code != FC_OK) {
        fc_mesh_geometry_unref(g);
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    }
    if (g)
        fc_mesh_set_put(set, g);
    else
        fc_mesh_set_remove(set, id);
    fc_viewer_view_changed(c, fc_monotonic_ms());
    return FC_CONV_CONTINUE;
}

/* MESH_TRANSFORM: all entries move, or none. */
static fc_conversation_verdict handle_mesh_transform(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                                     const uint8_t *payload, fc_buf *out)
{
    fc_error err;
    fc_mesh_transform entries[FC_MESH_MAX_COUNT];
    uint32_t count = 0;
    fc_code code = fc_wire_read_mesh_transforms(payload, h->length, entries, &count, &err);
    if (code == FC_OK)
        code = fc_mesh_set_move(mesh_set_of(c), entries, count, &err);
    if (code != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    fc_viewer_view_changed(c, fc_monotonic_ms());
    return FC_CONV_CONTINUE;
}

/* A RENDER goes to the GL thread; its IMAGE (or ERROR) is queued by
 * fc_conversation_job_done, and until then the connection reads nothing more, so
 * replies stay in request order. Without a CAMERA the frame is framed at the
 * viewer's size, or the default size, which must fit the limits. */
static fc_conversation_verdict handle_render(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                             const uint8_t *payload, double received_ms, fc_buf *out)
{
    fc_render_order order = {.kind = FC_JOB_REPLY, .request_id = h->request_id, .received_ms = received_ms};
    bool viewer = c->role == FC_ROLE_VIEWER;
    order.auto_width = viewer ? c->viewer.auto_width : FC_DEFAULT_VIEW_WIDTH;
    order.auto_height = viewer ? c->viewer.auto_height : FC_DEFAULT_VIEW_HEIGHT;
    fc_shared_frame *frame = fc_conversation_current_frame(c);
    fc_error err;
    fc_code code = fc_wire_read_render(payload, h->length, &order.request, &err);
    if (code == FC_OK && !frame)
        code = fc_error_set(&err, FC_ERR_BAD_STATE, "RENDER before any FRAME");
    if (code == FC_OK && !c->has_camera)
        code = fc_conversation_check_image_limit(&ctx->welcome.limits, order.auto_width, order.auto_height, &err);
    if (code == FC_OK)
        code = fc_conversation_submit_render(c, frame, &order, &err);
    if (code != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    c->reply_pending = true;
    return FC_CONV_CONTINUE;
}

/* SURFACE: the surface of the frame a RENDER would render, extracted on the GL
 * thread like a render; its parts answer it in its place among the replies. */
static fc_conversation_verdict handle_surface(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                              const uint8_t *payload, double received_ms, fc_buf *out)
{
    fc_render_order order = {.kind = FC_JOB_SURFACE, .request_id = h->request_id, .received_ms = received_ms};
    fc_shared_frame *frame = fc_conversation_current_frame(c);
    fc_error err;
    fc_code code = fc_wire_read_surface_request(payload, h->length, &order.surface_attributes, &err);
    if (code == FC_OK && !frame)
        code = fc_error_set(&err, FC_ERR_BAD_STATE, "SURFACE before any FRAME");
    if (code == FC_OK)
        code = fc_conversation_submit_render(c, frame, &order, &err);
    if (code != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
    c->reply_pending = true;
    return FC_CONV_CONTINUE;
}

/* The connection closes after GOODBYE either way; a malformed one is still answered. */
static fc_conversation_verdict handle_goodbye(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                              const uint8_t *payload, fc_buf *out)
{
    fc_error err;
    if (fc_wire_read_goodbye(payload, h->length, &err) != FC_OK)
        return reply_error(c, ctx, h, &err, FC_CONV_CLOSE, out);
    fc_log_write(ctx->log, FC_LOG_DEBUG, "%s: GOODBYE", c->peer);
    return FC_CONV_CLOSE;
}

bool fc_conversation_unauthenticated(const fc_conversation *c)
{
    return c->state == FC_CONV_AWAIT_HELLO && c->ctx->token && fc_auth_token_required(c->ctx->token);
}

/* With a token configured, nothing about the server (not even which protocol
 * errors it finds) is revealed before the client proved it knows the token. */
static fc_conversation_verdict authenticate_hello(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                                  const uint8_t *payload, fc_buf *out)
{
    fc_hello hello;
    fc_error err;
    if (h->type != FC_MSG_HELLO)
        fc_error_set(&err, FC_ERR_UNAUTHORIZED, "authentication required: send HELLO with the token first");
    else if (fc_wire_read_hello(payload, h->length, &hello, &err) != FC_OK || hello.token[0] == '\0')
        fc_error_set(&err, FC_ERR_UNAUTHORIZED, "authentication required: HELLO carries no readable token");
    else if (!fc_auth_token_matches(ctx->token->text, hello.token))
        fc_error_set(&err, FC_ERR_UNAUTHORIZED, "wrong token");
    else
        return handle_hello(c, ctx, h, payload, out);
    return reply_error(c, ctx, h, &err, FC_CONV_CLOSE, out);
}

/* Before the handshake only HELLO (or a polite GOODBYE) is accepted; any
 * other message ends the connection, as the client is not speaking fluidcast. */
static fc_conversation_verdict handle_before_hello(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                                   const uint8_t *payload, fc_buf *out)
{
    if (h->type == FC_MSG_HELLO)
        return handle_hello(c, ctx, h, payload, out);
    if (h->type == FC_MSG_GOODBYE)
        return handle_goodbye(c, ctx, h, payload, out);
    fc_error err;
    if (!is_defined_without_capabilities(h->type))
        fc_error_set(&err, FC_ERR_UNKNOWN_TYPE, "message type %u is not defined", (unsigned)h->type);
    else
        fc_error_set(&err, FC_ERR_BAD_STATE, "%s before HELLO", fc_msg_name(h->type));
    return reply_error(c, ctx, h, &err, FC_CONV_CLOSE, out);
}

/* Messages a client must not send once READY. */
static fc_conversation_verdict refuse_after_hello(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                                  fc_buf *out)
{
    fc_error err;
    if (h->type == FC_MSG_HELLO)
        fc_error_set(&err, FC_ERR_BAD_STATE, "HELLO was already answered");
    else if (h->type == FC_MSG_WELCOME || h->type == FC_MSG_IMAGE || h->type == FC_MSG_ERROR ||
             h->type == FC_MSG_SURFACE_PART)
        fc_error_set(&err, FC_ERR_BAD_STATE, "%s is sent by servers, not clients", fc_msg_name(h->type));
    else
        fc_error_set(&err, FC_ERR_UNKNOWN_TYPE, "message type %u is not defined in protocol version %u",
                     (unsigned)h->type, FC_PROTOCOL_VERSION);
    return reply_error(c, ctx, h, &err, FC_CONV_CONTINUE, out);
}

fc_conversation_verdict fc_conversation_handle(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *header,
                                               fc_payload *message, double received_ms, fc_buf *out)
{
    const uint8_t *payload = message->bytes;
    if (fc_conversation_unauthenticated(c))
        return authenticate_hello(c, ctx, header, payload, out);
    if (c->state == FC_CONV_AWAIT_HELLO)
        return handle_before_hello(c, ctx, header, payload, out);
    switch (header->type) {
    case FC_MSG_FRAME:
        return handle_frame(c, ctx, header, message, received_ms, out);
    case FC_MSG_CAMERA:
        return handle_camera(c, ctx, header, payload, out);
    case FC_MSG_SETTINGS:
        return handle_settings(c, ctx, header, payload, out);
    case FC_MSG_RENDER:
        return handle_render(c, ctx, header, payload, received_ms, out);
    case FC_MSG_SURFACE:
        return handle_surface(c, ctx, header, payload, received_ms, out);
    case FC_MSG_GOODBYE:
        return handle_goodbye(c, ctx, header, payload, out);
    case FC_MSG_BACKGROUND:
    case FC_MSG_ENVIRONMENT:
        return handle_scene_image(c, ctx, header, payload, out);
    case FC_MSG_MESH:
        return handle_mesh(c, ctx, header, payload, out);
    case FC_MSG_MESH_TRANSFORM:
        return handle_mesh_transform(c, ctx, header, payload, out);
    default:
        if (fc_conversation_is_session_message(header->type))
            return fc_conversation_handle_session_message(c, ctx, header, message, received_ms, out);
        return refuse_after_hello(c, ctx, header, out);
    }
}

/* ---- What the connection reports ---- */

void fc_conversation_job_done(fc_conversation *c, const fc_render_job *job)
{
    if (job->kind == FC_JOB_STREAM) {
        fc_viewer_job_done(c, job);
        return;
    }
    c->reply_pending = false;
    if (job->error.code != FC_OK) {
        fc_conversation_send_error(c, job->request_id, &job->error);
        return;
    }
    fc_error err;
    /* A reply that does not fit leaves the queue as it was, so an ERROR can still follow. */
    const char *what = job->kind == FC_JOB_SURFACE ? "the surface mesh" : "the IMAGE";
    if (fc_conversation_queue_message(c, &job->message, what, &err) != FC_OK) {
        fc_conversation_send_error(c, job->request_id, &err);
        return;
    }
    fc_log_write(c->ctx->log, FC_LOG_DEBUG, "%s: request %u: %s of %zu bytes queued", c->peer,
                 (unsigned)job->request_id, what, job->message.len);
}

void fc_conversation_output_drained(fc_conversation *c)
{
    fc_viewer_drained(c);
}

size_t fc_conversation_backlog_allowance(const fc_conversation *c)
{
    return fc_viewer_backlog_allowance(c);
}

double fc_conversation_deadline_ms(const fc_conversation *c)
{
    return fc_viewer_deadline_ms(c);
}

void fc_conversation_tick(fc_conversation *c, double now_ms)
{
    fc_viewer_tick(c, now_ms);
}
