/* session.h — one client's protocol state and the dispatch of its messages:
 * the handshake, the current frame, camera and settings, and the replies. */
#ifndef FC_DAEMON_SESSION_H
#define FC_DAEMON_SESSION_H

#include <stdbool.h>

#include "daemon_context.h"

typedef enum fc_session_state {
    FC_SESSION_AWAIT_HELLO = 0,
    FC_SESSION_READY
} fc_session_state;

typedef struct fc_session {
    fc_session_state state;
    const char *peer;        /* "ADDR:PORT" for logs; owned by the connection */
    bool has_frame;
    fc_scene scene;
    bool has_camera;
    fc_camera camera;
    fc_settings settings;
} fc_session;

/* What the connection does after a message has been handled. */
typedef enum fc_session_verdict {
    FC_SESSION_CONTINUE = 0,    /* keep reading */
    FC_SESSION_CLOSE,           /* flush the replies, then close */
    FC_SESSION_ABORT            /* no reply could be queued: close now */
} fc_session_verdict;

void fc_session_init(fc_session *s, const char *peer);
void fc_session_free(fc_session *s);

/* Handles one complete message (payload is header->length bytes), appending
 * any reply (WELCOME, IMAGE, ERROR) to out. received_ms: when it arrived. */
fc_session_verdict fc_session_handle(fc_session *s, fc_daemon_context *ctx, const fc_msg_header *header,
                                     const uint8_t *payload, double received_ms, fc_buf *out);

/* Appends an ERROR answering request_id; local codes become the nearest wire
 * code. Used for framing errors too, which the connection detects. */
fc_session_verdict fc_session_reply_error(const fc_daemon_context *ctx, const char *peer, uint32_t request_id,
                                          const fc_error *error, fc_session_verdict then, fc_buf *out);

#endif
