/* event_loop.h — the daemon's single-threaded poll() loop over the listening
 * socket, the stop signal and every client connection. */
#ifndef FC_DAEMON_EVENT_LOOP_H
#define FC_DAEMON_EVENT_LOOP_H

#include "daemon_context.h"

typedef struct fc_event_loop fc_event_loop;

/* listen_fd: a non-blocking listening socket; stop_fd: becomes readable when
 * the daemon must stop (a signalfd). Neither is owned by the loop. */
fc_code fc_event_loop_create(int listen_fd, int stop_fd, fc_daemon_context *ctx, fc_event_loop **out,
                             fc_error *err);

/* Serves clients until stop_fd is readable (FC_OK) or poll() fails (FC_ERR_IO). */
fc_code fc_event_loop_run(fc_event_loop *loop, fc_error *err);

/* Closes every client connection and frees the loop. */
void fc_event_loop_destroy(fc_event_loop *loop);

#endif
