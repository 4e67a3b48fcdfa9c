/* daemon_context.h — what every connection of the daemon shares: read-only
 * configuration plus the single render service. */
#ifndef FC_DAEMON_CONTEXT_H
#define FC_DAEMON_CONTEXT_H

#include "log.h"
#include "render_service.h"
#include "wire.h"

typedef struct fc_daemon_context {
    const fc_log *log;
    fc_welcome welcome;            /* sent to every client; its limits are the ones enforced */
    fc_render_service *render;
} fc_daemon_context;

#endif
