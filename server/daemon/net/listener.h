/* listener.h — the daemon's listening sockets: TCP (IPv4, IPv6, host names)
 * and Unix-domain (a path in the file system). */
#ifndef FC_DAEMON_LISTENER_H
#define FC_DAEMON_LISTENER_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "net/tls_server.h"

typedef struct fc_listener {
    int fd;                /* non-blocking, close-on-exec; -1 when closed */
    uint16_t port;         /* the bound TCP port (the kernel's choice for port 0); 0 for Unix */
    char address[128];     /* "127.0.0.1:7450", "[::1]:7450" or "unix:/run/fc.sock", for logs */
    bool is_unix;
    bool adopted;          /* handed over by the service manager: its socket file is not ours to remove */
    char unix_path[108];   /* the socket file, removed again on close (unless adopted) */
    fc_tls_server *tls;    /* TCP with --tls-cert: its connections speak TLS; NULL: in clear. Not owned */
} fc_listener;

/* Resolves host/port with getaddrinfo and listens on the first address that
 * binds. FC_ERR_IO naming every address tried when none does. */
fc_code fc_listener_open(const char *host, const char *port, fc_listener *out, fc_error *err);
/* Listens on a Unix-domain socket at path. A socket file left behind by a
 * daemon that is gone is replaced; one a running daemon answers on is not
 * (FC_ERR_IO: in use). */
fc_code fc_listener_open_unix(const char *path, fc_listener *out, fc_error *err);
/* Takes over a socket that already listens (socket activation: systemd passes
 * it as an inherited descriptor): TCP or Unix stream, made non-blocking and
 * close-on-exec, described like one opened here. Its socket file (Unix) stays
 * where the service manager made it on close. FC_ERR_IO when fd is not a
 * listening stream socket of those families. */
fc_code fc_listener_adopt(int fd, fc_listener *out, fc_error *err);
void fc_listener_close(fc_listener *l);

/* "ADDR:PORT" ("[ADDR]:PORT" for IPv6) of a socket address. */
void fc_format_sockaddr(const void *addr, char *out, size_t size);

#endif
