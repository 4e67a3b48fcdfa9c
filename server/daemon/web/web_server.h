/* web_server.h — the web viewer's endpoint (fluidcastd --web-listen, docs/web.md):
 * libwebsockets on a thread of its own serves the page's files (built into the
 * binary, web_assets.h) with a strict Content-Security-Policy, and relays each
 * WebSocket to a connection of the daemon's event loop (web_relay.h) through a
 * private Unix-domain socket, the *relay listener*, in a folder only the
 * daemon's user can enter. The event loop serves that listener like its
 * others, so everything it enforces applies to browsers unchanged. */
#ifndef FC_DAEMON_WEB_SERVER_H
#define FC_DAEMON_WEB_SERVER_H

#include "fluidcast_types.h"
#include "log.h"
#include "net/listener.h"
#include "net/tls_server.h"

typedef struct fc_web_server fc_web_server;

/* Listens on host:port (fc_listener_open's rules: port 0 = any free port),
 * opens the relay listener and starts serving: over HTTPS and WSS with the
 * protocol listeners' TLS server (their certificate, key and client CAs,
 * reloaded with theirs), over plain HTTP when tls is NULL. tls and log must
 * outlive the server. FC_ERR_IO when a socket cannot be opened or
 * libwebsockets cannot start (or load the certificate). */
fc_code fc_web_server_start(const char *host, const char *port, fc_tls_server *tls, const fc_log *log,
                            fc_web_server **out, fc_error *err);
/* The relay listener, for the event loop to accept from; owned by the server. */
const fc_listener *fc_web_server_relay(const fc_web_server *server);
/* "127.0.0.1:7451": where the page is served. */
const char *fc_web_server_address(const fc_web_server *server);
/* "https" with a certificate, else "http". */
const char *fc_web_server_scheme(const fc_web_server *server);
/* Stops the thread, closes every socket and removes the relay's folder; NULL is fine. */
void fc_web_server_stop(fc_web_server *server);

#endif
