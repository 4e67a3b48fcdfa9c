/* connection.h — one client socket: reads whole messages (header, then
 * payload), hands them to its conversation (conversations/conversation.h),
 * queues the replies (and a viewer's stream images) and flushes them as the
 * socket accepts them. All I/O is
 * non-blocking and goes through the connection's transport (transport.h):
 * in clear, or TLS after a handshake run step by step in this same loop. The
 * event loop calls in when poll() reports the socket ready, when a timer is
 * due, or when a render job of this connection finished. */
#ifndef FC_DAEMON_CONNECTION_H
#define FC_DAEMON_CONNECTION_H

#include <stdbool.h>
#include <stddef.h>

#include "conversations/conversation.h"
#include "net/transport.h"

typedef enum fc_connection_phase {
    FC_CONN_OPEN = 0,      /* reading and answering messages */
    FC_CONN_FLUSHING,      /* reading stopped: send what is queued, then close */
    FC_CONN_LINGERING,     /* all sent and writing shut down: discard input until the peer closes */
    FC_CONN_DONE,          /* to be destroyed */
    FC_CONN_HANDSHAKE      /* TLS handshake under way: no message read yet */
} fc_connection_phase;

typedef struct fc_connection {
    uint64_t id;                            /* process-unique: render jobs find their connection by it */
    fc_transport transport;                 /* the socket, and its TLS session if any */
    double handshake_deadline_ms;           /* FC_CONN_HANDSHAKE: when it is dropped as stalled */
    bool refuse_when_open;                  /* beyond --max-connections: refused once the handshake is done */
    char peer[80];                          /* "ADDR:PORT", for logs */
    fc_connection_phase phase;
    bool peer_closed;                       /* EOF seen: nothing to linger for */
    double linger_deadline_ms;
    double backlog_check_ms;                /* when to look at the kernel's send queue again; <= 0: not waiting */
    unsigned long messages;                 /* messages handled so far */
    double last_message_ms;                 /* when the connection opened or its last message completed */
    /* the message being read */
    uint8_t header_bytes[FC_WIRE_HEADER_SIZE];
    size_t header_got;
    double started_ms;                      /* when its first byte arrived */
    bool have_header;
    fc_msg_header header;
    fc_error header_error;                  /* a header fault that still lets the payload be skipped */
    uint8_t *payload;
    size_t payload_cap;
    size_t payload_got;
    /* replies not yet sent */
    fc_buf out;
    size_t out_sent;
    fc_conversation conversation;
} fc_connection;

/* Takes ownership of the connected, non-blocking socket fd; with tls (not
 * NULL) the connection starts with a TLS handshake under the daemon's
 * handshake timeout. */
fc_code fc_connection_create(int fd, const char *peer, uint64_t id, fc_tls_server *tls, fc_daemon_context *ctx,
                             fc_connection **out, fc_error *err);
/* Closes the socket, leaves any named session and frees everything. */
void fc_connection_destroy(fc_connection *c);

/* Answers a connection beyond --max-connections with ERROR LIMIT (request id 0) and closes it. */
void fc_connection_refuse(fc_connection *c, fc_daemon_context *ctx);

/* The poll() events the connection waits for now (0 when done). */
short fc_connection_wanted_events(const fc_connection *c);
/* Milliseconds until the connection needs a call without I/O, -1 for never. */
int fc_connection_timeout_ms(const fc_connection *c, double now_ms);
/* Acts on poll()'s revents (possibly 0, for a timeout). */
void fc_connection_on_events(fc_connection *c, short revents, fc_daemon_context *ctx);
/* A render job of this connection finished: queue its result and send what can be sent. */
void fc_connection_on_job_done(fc_connection *c, const fc_render_job *job);

static inline bool fc_connection_done(const fc_connection *c)
{
    return c->phase == FC_CONN_DONE;
}

#endif
