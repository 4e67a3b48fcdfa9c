/* daemon_context.h — what every connection of the daemon shares: the
 * configuration, the render service and the named sessions. Used from the
 * event-loop thread only (the render service does its own locking). */
#ifndef FC_DAEMON_CONTEXT_H
#define FC_DAEMON_CONTEXT_H

#include <stdint.h>

#include "auth_token.h"
#include "gpu/render_service.h"
#include "log.h"
#include "metrics/metrics.h"
#include "sessions/session_registry.h"
#include "wire.h"

typedef struct fc_daemon_context {
    const fc_log *log;
    fc_welcome welcome;            /* sent to every client (capabilities: as granted to it); its limits are enforced */
    fc_render_service *render;
    fc_session_registry *sessions;
    struct fc_frame_pool *frames;  /* the blocks frames live in, recycled (frame_pool.h) */
    double chunk_timeout_ms;       /* how long a multi-rank frame may wait for its last chunk */
    double refresh_ms;             /* quiet time after a lossy stream image before a lossless refresh; 0 = never */
    uint64_t last_frame_id;        /* frame ids handed out so far (see fc_shared_frame.id) */
    const fc_auth_token *token;    /* the secret HELLO must carry; text "" = none */
    uint32_t max_connections;      /* connections at once; more are refused with LIMIT */
    double idle_timeout_ms;        /* no complete message for this long closes a connection; 0 = never */
    double read_timeout_ms;        /* a started message must complete within this; 0 = never */
    double tls_handshake_timeout_ms; /* a TLS handshake must complete within this, or the connection is dropped */
    uint64_t max_session_memory;   /* bytes one connection may hold (conversations/conversation_memory.h) */
    fc_metrics *metrics;           /* counted by every layer, read by the metrics endpoint's thread */
} fc_daemon_context;

#endif
