/* service_manager.c — readiness notification and socket activation through
 * libsystemd (sd-daemon), which implements both protocols as systemd defines them. */
#include "service_manager.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <systemd/sd-daemon.h>
#include <unistd.h>

#include "fc_error.h"

void fc_service_notify(const fc_log *log, const char *format, ...)
{
    char state[512];
    va_list args;
    va_start(args, format);
    vsnprintf(state, sizeof state, format, args);
    va_end(args);
    int rc = sd_notify(0, state);
    if (rc < 0)
        fc_log_write(log, FC_LOG_DEBUG, "cannot notify the service manager: %s", strerror(-rc));
}

static bool is_metrics_name(char **names, int index)
{
    return names && names[index] && strcmp(names[index], FC_SERVICE_METRICS_FD_NAME) == 0;
}

static void free_names(char **names)
{
    for (size_t i = 0; names && names[i]; i++)
        free(names[i]);
    free(names);
}

/* One inherited descriptor as a render listener: a listening TCP (v4 or v6)
 * or Unix stream socket, nothing else. */
static fc_code adopt_render_socket(int fd, fc_listener *out, fc_error *err)
{
    if (sd_is_socket_inet(fd, AF_UNSPEC, SOCK_STREAM, 1, 0) <= 0 && sd_is_socket_unix(fd, SOCK_STREAM, 1, NULL, 0) <= 0)
        return fc_error_set(err, FC_ERR_IO,
                            "socket activation: descriptor %d is not a listening TCP or Unix stream socket "
                            "(ListenStream= in the .socket unit, Accept=no)",
                            fd);
    return fc_listener_adopt(fd, out, err);
}

fc_code fc_service_listeners(fc_listener *out, size_t max, size_t *count, int *metrics_fd, fc_error *err)
{
    *count = 0;
    *metrics_fd = -1;
    char **names = NULL;
    int n = sd_listen_fds_with_names(1, &names);
    if (n < 0)
        return fc_error_set(err, FC_ERR_IO, "socket activation: LISTEN_FDS: %s", strerror(-n));
    fc_code code = FC_OK;
    for (int i = 0; i < n && code == FC_OK; i++) {
        int fd = SD_LISTEN_FDS_START + i;
        if (is_metrics_name(names, i) && *metrics_fd < 0) {
            if (sd_is_socket_inet(fd, AF_UNSPEC, SOCK_STREAM, 1, 0) <= 0)
                code = fc_error_set(err, FC_ERR_IO,
                                    "socket activation: the '%s' descriptor %d is not a listening TCP socket",
                                    FC_SERVICE_METRICS_FD_NAME, fd);
            *metrics_fd = fd;
        } else if (*count == max) {
            code = fc_error_set(err, FC_ERR_IO, "socket activation: more than %zu sockets passed", max);
        } else {
            code = adopt_render_socket(fd, &out[*count], err);
            *count += code == FC_OK;
        }
    }
    free_names(names);
    return code;
}
