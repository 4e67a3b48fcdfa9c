/* socket_io.c — see socket_io.h. */
#include "socket_io.h"

#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"

static int64_t monotonic_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static int set_nonblocking(int fd, int on)
{
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0)
        return -1;
    return fcntl(fd, F_SETFL, on ? flags | O_NONBLOCK : flags & ~O_NONBLOCK);
}

/* Waits for a non-blocking connect to finish, retrying poll after signals with
 * the time that is left. Returns 0, or an errno value (ETIMEDOUT on timeout). */
static int wait_connected(int fd, uint32_t timeout_ms)
{
    int64_t deadline = monotonic_ms() + timeout_ms;
    for (;;) {
        int64_t left = deadline - monotonic_ms();
        if (left <= 0)
            return ETIMEDOUT;
        struct pollfd pfd = { .fd = fd, .events = POLLOUT };
        int ready = poll(&pfd, 1, (int)left);
        if (ready < 0 && errno == EINTR)
            continue;
        if (ready < 0)
            return errno;
        if (ready == 0)
            return ETIMEDOUT;
        int so_error = 0;
        socklen_t len = sizeof so_error;
        if (getsockopt(fd, SOL_SOCKET, SO_ERROR, &so_error, &len) < 0)
            return errno;
        return so_error;
    }
}

/* Returns a connected blocking socket, or -1 with the errno value in *error. */
static int connect_address(const struct addrinfo *ai, uint32_t timeout_ms, int *error)
{
    int fd = socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) {
        *error = errno;
        return -1;
    }
    int status = 0;
    if (set_nonblocking(fd, 1) < 0)
        status = errno;
    else if (connect(fd, ai->ai_addr, ai->ai_addrlen) < 0)
        status = (errno == EINPROGRESS || errno == EINTR) ? wait_connected(fd, timeout_ms) : errno;
    if (status == 0 && set_nonblocking(fd, 0) < 0)
        status = errno;
    if (status != 0) {
        close(fd);
        *error = status;
        return -1;
    }
    /* Messages are written whole; waiting for more bytes only delays replies. */
    int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    return fd;
}

fc_code fc_socket_connect(const char *host, const char *port, uint32_t timeout_ms, int *fd_out,
                          fc_error *err)
{
    *fd_out = -1;
    struct addrinfo hints;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_NUMERICSERV;
    struct addrinfo *list = NULL;
    int gai = getaddrinfo(host, port, &hints, &list);
    if (gai != 0)
        return fc_error_set(err, FC_ERR_CONNECT, "cannot resolve %s: %s", host, gai_strerror(gai));

    int last_error = ECONNREFUSED;
    for (const struct addrinfo *ai = list; ai; ai = ai->ai_next) {
        int fd = connect_address(ai, timeout_ms, &last_error);
        if (fd >= 0) {
            freeaddrinfo(list);
            *fd_out = fd;
            return FC_OK;
        }
    }
    freeaddrinfo(list);
    return fc_error_set(err, FC_ERR_CONNECT, "cannot connect to %s port %s: %s", host, port,
                        strerror(last_error));
}

fc_code fc_socket_connect_unix(const char *path, int *fd_out, fc_error *err)
{
    *fd_out = -1;
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    if (path[0] == '\0' || strlen(path) >= sizeof addr.sun_path)
        return fc_error_set(err, FC_ERR_USAGE, "unix socket path must have 1 to %zu bytes",
                            sizeof addr.sun_path - 1);
    memcpy(addr.sun_path, path, strlen(path));
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return fc_error_set(err, FC_ERR_CONNECT, "socket: %s", strerror(errno));
    if (connect(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        int saved = errno;
        close(fd);
        return fc_error_set(err, FC_ERR_CONNECT, "cannot connect to unix:%s: %s", path, strerror(saved));
    }
    *fd_out = fd;
    return FC_OK;
}

fc_code fc_socket_set_timeout(int fd, uint32_t timeout_ms, fc_error *err)
{
    struct timeval tv = { .tv_sec = timeout_ms / 1000, .tv_usec = (timeout_ms % 1000) * 1000 };
    if (setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv) < 0 ||
        setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv) < 0)
        return fc_error_set(err, FC_ERR_IO, "cannot set socket timeout: %s", strerror(errno));
    return FC_OK;
}

static fc_code transfer_failure(int error, const char *what, fc_error *err)
{
    if (error == EAGAIN || error == EWOULDBLOCK)
        return fc_error_set(err, FC_ERR_IO, "timed out %s the server", what);
    if (error == EPIPE || error == ECONNRESET)
        return fc_error_set(err, FC_ERR_CLOSED, "the server closed the connection");
    return fc_error_set(err, FC_ERR_IO, "socket failure %s the server: %s", what, strerror(error));
}

fc_code fc_socket_send_all(int fd, const uint8_t *data, size_t n, fc_error *err)
{
    while (n > 0) {
        /* MSG_NOSIGNAL: a vanished server is an error value, not a SIGPIPE that
         * would kill the simulation hosting this library. */
        ssize_t sent = send(fd, data, n, MSG_NOSIGNAL);
        if (sent < 0 && errno == EINTR)
            continue;
        if (sent < 0)
            return transfer_failure(errno, "sending to", err);
        data += sent;
        n -= (size_t)sent;
    }
    return FC_OK;
}

fc_code fc_socket_send_parts(int fd, struct iovec *parts, size_t count, fc_error *err)
{
    while (count > 0) {
        struct msghdr message = {.msg_iov = parts, .msg_iovlen = count};
        ssize_t sent = sendmsg(fd, &message, MSG_NOSIGNAL);
        if (sent < 0 && errno == EINTR)
            continue;
        if (sent < 0)
            return transfer_failure(errno, "sending to", err);
        /* Skip what went out: whole parts, then the front of a partly sent one. */
        size_t left = (size_t)sent;
        while (count > 0 && left >= parts->iov_len) {
            left -= parts->iov_len;
            parts++;
            count--;
        }
        if (count > 0) {
            parts->iov_base = (uint8_t *)parts->iov_base + left;
            parts->iov_len -= left;
        }
    }
    return FC_OK;
}

fc_code fc_socket_recv_exact(int fd, uint8_t *data, size_t n, fc_error *err)
{
    while (n > 0) {
        ssize_t got = recv(fd, data, n, 0);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0)
            return transfer_failure(errno, "waiting for", err);
        if (got == 0)
            return fc_error_set(err, FC_ERR_CLOSED, "the server closed the connection");
        data += got;
        n -= (size_t)got;
    }
    return FC_OK;
}
