/* session_member.h — how a named session talks to the connections in it.
 *
 * A session knows its producers and viewers only as members: a handle with a
 * table of functions, which whoever joins fills in (the conversations layer:
 * conversations/conversation_sessions.c) and embeds in its own state. The
 * session calls its members through that table, never by name, so no file of
 * the session layer includes a conversation header and the dependencies run
 * one way: conversations -> sessions. Event-loop thread only. */
#ifndef FC_DAEMON_SESSION_MEMBER_H
#define FC_DAEMON_SESSION_MEMBER_H

#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_session_member fc_session_member;

/* What a session tells its members. Each may be called from inside the
 * session's own functions (fc_session_publish, fc_session_remove_producer,
 * fc_registry_expire), and may leave the session from there. */
typedef struct fc_session_member_ops {
    /* To a viewer: its session published a new frame. */
    void (*new_frame)(fc_session_member *viewer);
    /* To a viewer: its session lost its last producer; the viewer gets what
     * is pending, then SESSION_END, and stays in the ended session. */
    void (*session_ended)(fc_session_member *viewer);
    /* To a producer: a multi-rank frame it sent a chunk of (request
     * `request_id`) failed with `err` (FC_ERR_INCOMPLETE). */
    void (*chunk_failed)(fc_session_member *producer, uint32_t request_id, const fc_error *err);
} fc_session_member_ops;

/* Embedded in the state of whoever joins a session, which finds itself from
 * it (offsetof); the session keeps pointers to it while the member is in. */
struct fc_session_member {
    const fc_session_member_ops *ops;
};

#endif
