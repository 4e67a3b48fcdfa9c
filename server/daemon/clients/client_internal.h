/* client_internal.h — what the client sources share (client.c,
 * client_sessions.c, viewer.c, client_render.c, client_reply.c), grouped by
 * the file that defines it, lowest first. Not used outside clients/. */
#ifndef FC_DAEMON_CLIENT_INTERNAL_H
#define FC_DAEMON_CLIENT_INTERNAL_H

#include <stddef.h>

#include "clients/client.h"

/* Without a CAMERA the frame is framed automatically at this size. */
enum { FC_DEFAULT_VIEW_WIDTH = 1280, FC_DEFAULT_VIEW_HEIGHT = 720 };

/* The client a session member is embedded in. */
static inline fc_client *fc_client_of_member(fc_session_member *member)
{
    return (fc_client *)((char *)member - offsetof(fc_client, member));
}

/* ---- client_reply.c ---- */

/* Appends an ERROR answering request_id to the client's output queue; the connection stays open. */
void fc_client_send_error(fc_client *c, uint32_t request_id, const fc_error *err);

/* Appends a whole message (`what`, e.g. "the IMAGE", for errors) to the
 * output queue. The queue is unchanged on failure: FC_ERR_LIMIT when it would
 * take the connection beyond its memory limit (client_memory.h),
 * FC_ERR_INTERNAL when out of memory. */
fc_code fc_client_queue_message(fc_client *c, const fc_buf *message, const char *what, fc_error *err);

/* ---- client_render.c ---- */

/* FC_ERR_LIMIT when width x height exceeds the server's image limit. */
fc_code fc_client_check_image_limit(const fc_limits *limits, uint32_t width, uint32_t height, fc_error *err);

/* What a render shows: the named session's newest frame, else the connection's own FRAME (NULL: none yet). */
fc_shared_frame *fc_client_current_frame(const fc_client *c);

/* One image to render for this client. */
typedef struct fc_render_order {
    fc_job_kind kind;
    uint32_t request_id;
    fc_render_request request;
    fc_stream_tag tag;             /* FC_JOB_STREAM only */
    fc_h264_stream *video;         /* an H.264 viewer's stream (the job takes a reference); NULL: none */
    bool force_keyframe;           /* H.264: the image must be an IDR frame */
    double received_ms;            /* what FC_STAGE_TOTAL counts from */
    uint32_t auto_width;           /* camera size when the client has no CAMERA */
    uint32_t auto_height;
} fc_render_order;

/* Queues the render of `frame` with the client's camera and settings. */
fc_code fc_client_submit_render(fc_client *c, fc_shared_frame *frame, const fc_render_order *order,
                                fc_error *err);

/* Gives a view that lies in the payload (no block) a block of its own: the
 * payload's, which it takes, when that is barely larger than the frame's
 * arrays (so what the frame holds stays what client_memory.h counts), else
 * a copy in a block from the pool. A view with a block is left as it is. */
fc_code fc_client_keep_payload(fc_client *c, fc_frame_view *view, fc_payload *payload, fc_error *err);

/* A decoded frame becomes the connection's current frame or, on a producer,
 * the named session's newest frame. Its block is taken either way (given back
 * to the pool on failure); a view without one first gets one with
 * fc_client_keep_payload. received_ms: when its last byte arrived;
 * decode_ms: how long decoding took. */
fc_code fc_client_take_frame(fc_client *c, fc_frame_view *view, fc_payload *payload, double received_ms,
                             double decode_ms, fc_error *err);

/* ---- client_sessions.c ---- */

/* Named-session and packed-upload messages: the types that need a capability (fc_msg_capabilities). */
bool fc_client_is_session_message(uint16_t type);
fc_client_verdict fc_client_handle_session_message(fc_client *c, fc_daemon_context *ctx, const fc_msg_header *h,
                                                   fc_payload *payload, double received_ms, fc_buf *out);

/* Leaves the named session without a word to this client (it has gone, or the caller answers). */
void fc_client_detach(fc_client *c);

#endif
