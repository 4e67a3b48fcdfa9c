/* session.h — one client's protocol state and the dispatch of its messages:
 * the handshake, the current frame, camera and settings, the replies, and its
 * part in a named session (producer or viewer; session_stream.c, viewer.c). */
#ifndef FC_DAEMON_SESSION_H
#define FC_DAEMON_SESSION_H

#include <stdbool.h>

#include "clients/viewer.h"
#include "daemon_context.h"
#include "gpu/render_job.h"
#include "uploads/foam_track.h"
#include "uploads/scene_uploads.h"

typedef enum fc_session_state {
    FC_SESSION_AWAIT_HELLO = 0,
    FC_SESSION_READY
} fc_session_state;

typedef enum fc_session_role {
    FC_ROLE_NONE = 0,        /* renders its own FRAMEs */
    FC_ROLE_PRODUCER,        /* publishes frames (or chunks of them) to a named session */
    FC_ROLE_VIEWER           /* receives a named session's frames as stream images */
} fc_session_role;

typedef struct fc_session {
    fc_session_state state;
    const char *peer;              /* "ADDR:PORT" for logs; owned by the connection */
    fc_daemon_context *ctx;        /* for what happens outside fc_session_handle: new frames, timers */
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
    fc_session_role role;
    struct fc_stream_session *stream;   /* the named session published or subscribed to; NULL when none */
    fc_viewer viewer;              /* role == FC_ROLE_VIEWER */
} fc_session;

/* What the connection does after a message has been handled. */
typedef enum fc_session_verdict {
    FC_SESSION_CONTINUE = 0,    /* keep reading */
    FC_SESSION_CLOSE,           /* flush the replies, then close */
    FC_SESSION_ABORT            /* no reply could be queued: close now */
} fc_session_verdict;

/* out: the connection's output queue, where replies and stream images go. */
void fc_session_init(fc_session *s, const char *peer, fc_daemon_context *ctx, uint64_t connection_id, fc_buf *out);
/* Leaves its named session (a producer's leaving may end it) and frees everything. */
void fc_session_free(fc_session *s);

/* A received payload in a block of `capacity` bytes (malloc'd, 4-byte
 * aligned), which a frame decoded in place may keep: then the session takes
 * it and sets bytes to NULL. */
typedef struct fc_payload {
    uint8_t *bytes;
    size_t capacity;
} fc_payload;

/* Handles one complete message (payload holds header->length bytes), appending
 * any immediate reply (WELCOME, ERROR, SESSION_STATE, ...) to out; a RENDER's
 * IMAGE follows through fc_session_job_done. received_ms: when it arrived. */
fc_session_verdict fc_session_handle(fc_session *s, fc_daemon_context *ctx, const fc_msg_header *header,
                                     fc_payload *payload, double received_ms, fc_buf *out);

/* Appends an ERROR answering request_id; local codes become the nearest wire
 * code. Used for framing errors too, which the connection detects. */
fc_session_verdict fc_session_reply_error(const fc_daemon_context *ctx, const char *peer, uint32_t request_id,
                                          const fc_error *error, fc_session_verdict then, fc_buf *out);

/* True while a token is required and this client has not presented it:
 * the only reply such a client may get is ERROR UNAUTHORIZED. */
bool fc_session_unauthenticated(const fc_session *s);

/* A render job of this session finished: its IMAGE / STREAM_IMAGE (or ERROR) is queued. */
void fc_session_job_done(fc_session *s, const fc_render_job *job);
/* The connection's output queue has been sent completely (and the kernel
 * holds no more than fc_session_backlog_allowance of it). */
void fc_session_output_drained(fc_session *s);
/* Bytes the kernel may still hold for this peer before fc_session_output_drained:
 * a viewer waiting to send its next image allows about one image; SIZE_MAX otherwise. */
size_t fc_session_backlog_allowance(const fc_session *s);
/* When the session next needs fc_session_tick (fc_monotonic_ms time); negative for never. */
double fc_session_deadline_ms(const fc_session *s);
void fc_session_tick(fc_session *s, double now_ms);

#endif
