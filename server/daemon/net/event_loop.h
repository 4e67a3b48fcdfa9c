/* event_loop.h — the daemon's single-threaded poll() loop over the stop
 * signal, the render service's results, the listening sockets and every
 * client connection, plus the timers of sessions and multi-rank frames. */
#ifndef FC_DAEMON_EVENT_LOOP_H
#define FC_DAEMON_EVENT_LOOP_H

#include <stddef.h>

#include "daemon_context.h"
#include "net/listener.h"

typedef struct fc_event_loop fc_event_loop;

/* listeners: `count` open listening sockets (TCP and/or Unix); stop_fd becomes
 * readable when the daemon must stop, reload_fd when the listeners' TLS
 * certificates and keys are to be read again (signalfds; reload_fd -1 for
 * none). None is owned by the loop; the listener array must outlive it. */
fc_code fc_event_loop_create(const fc_listener *listeners, size_t count, int stop_fd, int reload_fd,
                             fc_daemon_context *ctx, fc_event_loop **out, fc_error *err);

/* Serves clients until stop_fd is readable (FC_OK) or poll() fails (FC_ERR_IO). */
fc_code fc_event_loop_run(fc_event_loop *loop, fc_error *err);

/* After the stop signal: accepts and reads nothing more, but answers the
 * RENDERs already in flight and sends queued replies (for at most 5 s), so no
 * client loses a render it asked for. Separate from fc_event_loop_run so the
 * top level can say it is stopping (to systemd, to /readyz) in between. */
fc_code fc_event_loop_drain(fc_event_loop *loop, fc_error *err);

/* Closes every client connection and frees the loop. */
void fc_event_loop_destroy(fc_event_loop *loop);

#endif
