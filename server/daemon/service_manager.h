/* service_manager.h — fluidcastd under systemd, or anything that speaks its
 * two protocols: readiness notification (sd_notify: READY=1, STOPPING=1,
 * STATUS=) and socket activation (sockets inherited as LISTEN_FDS). Outside a
 * service manager (no NOTIFY_SOCKET, no LISTEN_FDS) both do nothing. */
#ifndef FC_DAEMON_SERVICE_MANAGER_H
#define FC_DAEMON_SERVICE_MANAGER_H

#include <stddef.h>

#include "fluidcast_types.h"
#include "log.h"
#include "net/listener.h"

/* The name (FileDescriptorName= in a .socket unit) that marks an inherited
 * socket as the metrics listener rather than a render port. */
#define FC_SERVICE_METRICS_FD_NAME "metrics"

/* Sends one state line ("READY=1", "STATUS=...", several separated by "\n")
 * to the service manager, formatted like printf. A failure to send is logged
 * at debug level only: the daemon serves the same either way. */
void fc_service_notify(const fc_log *log, const char *format, ...) __attribute__((format(printf, 2, 3)));

/* The sockets the service manager passed (LISTEN_FDS for this process), as
 * listeners: *count of them in out[0..max), TCP and Unix stream sockets told
 * apart with sd_is_socket_inet / sd_is_socket_unix. One named "metrics" goes
 * to *metrics_fd instead (-1 when none). The variables are removed from the
 * environment so that no child takes them for its own. *count 0 without
 * socket activation. FC_ERR_IO naming the descriptor when one is not a
 * listening stream socket, or there are more than max. */
fc_code fc_service_listeners(fc_listener *out, size_t max, size_t *count, int *metrics_fd, fc_error *err);

#endif
