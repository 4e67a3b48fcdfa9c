/* socket_io.h — blocking TCP socket helpers for the client: connecting with a
 * time limit, and sending/receiving exact byte counts through EINTR, partial
 * transfers and the peer going away. */
#ifndef FC_SOCKET_IO_H
#define FC_SOCKET_IO_H

#include <stddef.h>
#include <stdint.h>
#include <sys/uio.h>
#include "fluidcast_types.h"

/* Resolves host/port (IPv4 or IPv6) and connects to the first address that
 * accepts within timeout_ms each. On success *fd_out is a blocking socket with
 * TCP_NODELAY. FC_ERR_CONNECT naming the host and the last failure otherwise. */
fc_code fc_socket_connect(const char *host, const char *port, uint32_t timeout_ms, int *fd_out,
                          fc_error *err);

#define FC_UNIX_PREFIX "unix:"

/* Connects to the Unix-domain socket at path (blocking). FC_ERR_CONNECT
 * naming the path and the failure otherwise; FC_ERR_USAGE for a path too long
 * for a socket address. */
fc_code fc_socket_connect_unix(const char *path, int *fd_out, fc_error *err);

/* Bounds every later send/receive on fd to timeout_ms of silence (0: no bound). */
fc_code fc_socket_set_timeout(int fd, uint32_t timeout_ms, fc_error *err);

/* Sends all n bytes. FC_ERR_CLOSED when the peer has gone, FC_ERR_IO on a timeout
 * or another socket failure. Never raises SIGPIPE. */
fc_code fc_socket_send_all(int fd, const uint8_t *data, size_t n, fc_error *err);

/* Sends the count buffers of parts (a handful: at most the system's IOV_MAX) one
 * after the other, as fc_socket_send_all would their concatenation, without
 * concatenating them: large arrays go to the socket from where their owner keeps
 * them. Advances through parts (the array is changed). */
fc_code fc_socket_send_parts(int fd, struct iovec *parts, size_t count, fc_error *err);

/* Receives exactly n bytes. FC_ERR_CLOSED when the peer closes first,
 * FC_ERR_IO on a timeout or another socket failure. */
fc_code fc_socket_recv_exact(int fd, uint8_t *data, size_t n, fc_error *err);

#endif
