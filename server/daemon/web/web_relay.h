/* web_relay.h — one WebSocket of the web viewer relayed to a connection of
 * the daemon's own event loop. Each binary WebSocket message carries exactly
 * one protocol message (proto/PROTOCOL.md section 14): what the page sends is
 * written, byte for byte, to a Unix-domain connection to the daemon's private
 * relay socket, which the event loop serves like any client (limits, token,
 * hostile-input rules unchanged); what the daemon answers is cut at message
 * boundaries and sent back as one WebSocket message each. At most one chunk
 * of each direction waits in the relay: when the browser reads slowly the
 * daemon's socket fills and its latest-wins streaming applies as for any
 * viewer. Runs on the web server's thread (web_server.h). */
#ifndef FC_DAEMON_WEB_RELAY_H
#define FC_DAEMON_WEB_RELAY_H

#include <libwebsockets.h>

#include "log.h"

/* The WebSocket subprotocol a page asks for. */
#define FC_WEB_SUBPROTOCOL "fluidcast.v1"
/* The protocol name the daemon-side descriptors are adopted under. */
#define FC_WEB_RELAY_PROTOCOL "fluidcast-relay"

/* What every relay needs from its server: where the daemon's relay socket is
 * and the log. Passed as the protocols' user pointer. */
typedef struct fc_web_relay_config {
    const char *relay_path;
    const fc_log *log;
} fc_web_relay_config;

/* lws callbacks: the WebSocket side (subprotocol FC_WEB_SUBPROTOCOL, per-session
 * data fc_web_relay_size() bytes) and the daemon side (FC_WEB_RELAY_PROTOCOL,
 * raw file descriptors). */
int fc_web_relay_ws_callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in, size_t len);
int fc_web_relay_daemon_callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in,
                                 size_t len);
size_t fc_web_relay_size(void);

#endif
