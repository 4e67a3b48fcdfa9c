/* listener.h — the daemon's listening TCP socket (IPv4, IPv6, host names). */
#ifndef FC_DAEMON_LISTENER_H
#define FC_DAEMON_LISTENER_H

#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_listener {
    int fd;                /* non-blocking, close-on-exec; -1 when closed */
    uint16_t port;         /* the bound port (the kernel's choice for port 0) */
    char address[80];      /* "127.0.0.1:7450" or "[::1]:7450", for logs */
} fc_listener;

/* Resolves host/port with getaddrinfo and listens on the first address that
 * binds. FC_ERR_IO naming every address tried when none does. */
fc_code fc_listener_open(const char *host, const char *port, fc_listener *out, fc_error *err);
void fc_listener_close(fc_listener *l);

/* "ADDR:PORT" ("[ADDR]:PORT" for IPv6) of a socket address. */
void fc_format_sockaddr(const void *addr, char *out, size_t size);

#endif
