/* conversation.h — a conversation: one connection's protocol state (what its
 * client has said and is owed), and the dispatch of its messages: the
 * handshake, the current frame, camera and settings, the replies, and its part
 * in a named session (producer or viewer; conversation_sessions.c, viewer.c).
 * Not the library's fc_client (client/lib/fluidcast.h), the other end of the
 * connection. The word "session" means a named session only (sessions/); a
 * conversation is told of its session's events through the member it embeds
 * (sessions/session_member.h), so the session layer never calls back into
 * this one.
 *
 * The files of conversations/ call one another one way, top to bottom:
 *   conversation.c           handshake, dispatch, what the connection reports
 *   conversation_sessions.c  PUBLISH, SUBSCRIBE, SESSION_END, CHUNK, FRAME_PACKED,
 *                            LIST_SESSIONS; the member a session calls
 *   viewer.c                 a subscribed client's stream of images
 *   conversation_render.c    render jobs and frames from the conversation's state
 *   conversation_reply.c     ERROR replies, messages queued within the memory limit
 *   conversation_memory.c    what the conversation holds, against --max-session-memory */
#ifndef FC_DAEMON_CONVERSATION_H
#define FC_DAEMON_CONVERSATION_H

#include <stdbool.h>

#include "conversations/viewer.h"
#include "daemon_context.h"
#include "gpu/render_job.h"
#include "sessions/session_member.h"
#include "uploads/foam_track.h"
#include "uploads/mesh_uploads.h"
#include "uploads/scene_uploads.h"

typedef enum fc_conversation_state {
    FC_CONV_AWAIT_HELLO = 0,
    FC_CONV_READY
} fc_conversation_state;

typedef enum fc_conversation_role {
    FC_ROLE_NONE = 0,        /* renders its own FRAMEs */
    FC_ROLE_PRODUCER,        /* publishes frames (or chunks of them) to a named session */
    FC_ROLE_VIEWER           /* receives a named session's frames as stream images */
} fc_conversation_role;

typedef struct fc_conversation {
    fc_conversation_state state;
    const char *peer;              /* "ADDR:PORT" for logs; owned by the connection */
    fc_daemon_context *ctx;        /* for what happens outside fc_conversation_handle: new frames, timers */
    uint64_t connection_id;        /* routes render results back to this connection */
    fc_buf *out;                   /* the connection's output queue */
    uint32_t capabilities;         /* granted in WELCOME */
    double message_started_ms;     /* set by the connection: when the message being handled began to arrive */
    bool reply_pending;            /* a RENDER is being rendered: the connection reads nothing until it is answered */
    fc_shared_frame *frame;        /* the last FRAME, for renders outside named sessions */
    fc_foam_track *foam;           /* foam history of this connection's own FRAMEs; NULL before the first */
    bool has_camera;
    fc_camera camera;
    fc_settings settings;
    fc_scene_uploads scene;        /* BACKGROUND / ENVIRONMENT images for this connection's renders */
    fc_mesh_set meshes;            /* its own MESHes (a producer's go to its session) */
    fc_conversation_role role;
    struct fc_session *session;    /* the named session published or subscribed to; NULL when none */
    fc_session_member member;      /* how that session tells this conversation (conversation_sessions.c) */
    fc_viewer viewer;              /* role == FC_ROLE_VIEWER */
    uint64_t transport_bytes;      /* set by the connection: what its TLS session holds (0 in clear) */
} fc_conversation;

/* What the connection does after a message has been handled. */
typedef enum fc_conversation_verdict {
    FC_CONV_CONTINUE = 0,    /* keep reading */
    FC_CONV_CLOSE,           /* flush the replies, then close */
    FC_CONV_ABORT            /* no reply could be queued: close now */
} fc_conversation_verdict;

/* out: the connection's output queue, where replies and stream images go. */
void fc_conversation_init(fc_conversation *c, const char *peer, fc_daemon_context *ctx, uint64_t connection_id,
                          fc_buf *out);
/* Leaves its named session (a producer's leaving may end it) and frees everything. */
void fc_conversation_free(fc_conversation *c);

/* A received payload in a block of `capacity` bytes (malloc'd, 4-byte
 * aligned), which a frame decoded in place may keep: then the client takes
 * it and sets bytes to NULL. */
typedef struct fc_payload {
    uint8_t *bytes;
    size_t capacity;
} fc_payload;

/* Handles one complete message (payload holds header->length bytes), appending
 * any immediate reply (WELCOME, ERROR, SESSION_STATE, ...) to out; a RENDER's
 * IMAGE follows through fc_conversation_job_done. received_ms: when it arrived. */
fc_conversation_verdict fc_conversation_handle(fc_conversation *c, fc_daemon_context *ctx, const fc_msg_header *header,
                                               fc_payload *payload, double received_ms, fc_buf *out);

/* Appends an ERROR answering request_id; local codes become the nearest wire
 * code. Used for framing errors too, which the connection detects.
 * (conversation_reply.c) */
fc_conversation_verdict fc_conversation_reply_error(const fc_daemon_context *ctx, const char *peer, uint32_t request_id,
                                                    const fc_error *error, fc_conversation_verdict then, fc_buf *out);

/* True while a token is required and this client has not presented it:
 * the only reply such a client may get is ERROR UNAUTHORIZED. */
bool fc_conversation_unauthenticated(const fc_conversation *c);

/* A render job of this client finished: its IMAGE / STREAM_IMAGE (or ERROR) is queued. */
void fc_conversation_job_done(fc_conversation *c, const fc_render_job *job);
/* The connection's output queue has been sent completely (and the kernel
 * holds no more than fc_conversation_backlog_allowance of it). */
void fc_conversation_output_drained(fc_conversation *c);
/* Bytes the kernel may still hold for this peer before fc_conversation_output_drained:
 * a viewer waiting to send its next image allows about one image; SIZE_MAX otherwise. */
size_t fc_conversation_backlog_allowance(const fc_conversation *c);
/* When the client next needs fc_conversation_tick (fc_monotonic_ms time); negative for never. */
double fc_conversation_deadline_ms(const fc_conversation *c);
void fc_conversation_tick(fc_conversation *c, double now_ms);

#endif
