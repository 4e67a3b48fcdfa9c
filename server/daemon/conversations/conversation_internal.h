/* conversation_internal.h — what the conversation sources share (conversation.c,
 * conversation_sessions.c, viewer.c, conversation_render.c, conversation_reply.c),
 * grouped by the file that defines it, lowest first. Not used outside conversations/. */
#ifndef FC_DAEMON_CONVERSATION_INTERNAL_H
#define FC_DAEMON_CONVERSATION_INTERNAL_H

#include <stddef.h>

#include "conversations/conversation.h"

/* Without a CAMERA the frame is framed automatically at this size. */
enum { FC_DEFAULT_VIEW_WIDTH = 1280, FC_DEFAULT_VIEW_HEIGHT = 720 };

/* The conversation a session member is embedded in. */
static inline fc_conversation *fc_conversation_of_member(fc_session_member *member)
{
    return (fc_conversation *)((char *)member - offsetof(fc_conversation, member));
}

/* ---- conversation_reply.c ---- */

/* Appends an ERROR answering request_id to the client's output queue; the connection stays open. */
void fc_conversation_send_error(fc_conversation *c, uint32_t request_id, const fc_error *err);

/* Appends a whole message (`what`, e.g. "the IMAGE", for errors) to the
 * output queue. The queue is unchanged on failure: FC_ERR_LIMIT when it would
 * take the connection beyond its memory limit (conversation_memory.h),
 * FC_ERR_INTERNAL when out of memory. */
fc_code fc_conversation_queue_message(fc_conversation *c, const fc_buf *message, const char *what, fc_error *err);

/* ---- conversation_render.c ---- */

/* FC_ERR_LIMIT when width x height exceeds the server's image limit. */
fc_code fc_conversation_check_image_limit(const fc_limits *limits, uint32_t width, uint32_t height, fc_error *err);

/* What a render shows: the named session's newest frame, else the connection's own FRAME (NULL: none yet). */
fc_shared_frame *fc_conversation_current_frame(const fc_conversation *c);

/* One image to render for this client. */
typedef struct fc_render_order {
    fc_job_kind kind;
    uint32_t request_id;
    fc_render_request request;
    uint32_t surface_attributes;   /* FC_JOB_SURFACE only: the FC_SURFACE_* bits asked for */
    fc_stream_tag tag;             /* FC_JOB_STREAM only */
    fc_h264_stream *video;         /* an H.264 viewer's stream (the job takes a reference); NULL: none */
    bool force_keyframe;           /* H.264: the image must be an IDR frame */
    double received_ms;            /* what FC_STAGE_TOTAL counts from */
    uint32_t auto_width;           /* camera size when the client has no CAMERA */
    uint32_t auto_height;
} fc_render_order;

/* Queues the render of `frame` with the client's camera and settings. */
fc_code fc_conversation_submit_render(fc_conversation *c, fc_shared_frame *frame, const fc_render_order *order,
                                      fc_error *err);

/* Gives a view that lies in the payload (no block) a block of its own: the
 * payload's, which it takes, when that is barely larger than the frame's
 * arrays (so what the frame holds stays what conversation_memory.h counts), else
 * a copy in a block from the pool. A view with a block is left as it is. */
fc_code fc_conversation_keep_payload(fc_conversation *c, fc_frame_view *view, fc_payload *payload, fc_error *err);

/* A decoded frame becomes the connection's current frame or, on a producer,
 * the named session's newest frame. Its block is taken either way (given back
 * to the pool on failure); a view without one first gets one with
 * fc_conversation_keep_payload. received_ms: when its last byte arrived;
 * decode_ms: how long decoding took. */
fc_code fc_conversation_take_frame(fc_conversation *c, fc_frame_view *view, fc_payload *payload, double received_ms,
                                   double decode_ms, fc_error *err);

/* ---- conversation_sessions.c ---- */

/* Named-session and packed-upload messages: the types that need a capability (fc_msg_capabilities). */
bool fc_conversation_is_session_message(uint16_t type);
fc_conversation_verdict fc_conversation_handle_session_message(fc_conversation *c, fc_daemon_context *ctx,
                                                               const fc_msg_header *h, fc_payload *payload,
                                                               double received_ms, fc_buf *out);

/* Leaves the named session without a word to this client (it has gone, or the caller answers). */
void fc_conversation_detach(fc_conversation *c);

#endif
