/* listener.c — the daemon's listening sockets: opened here, or inherited from
 * the service manager (socket activation). */
#include "net/listener.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "fc_error.h"

enum { LISTEN_BACKLOG = 64 };

void fc_format_sockaddr(const void *addr, char *out, size_t size)
{
    const struct sockaddr *sa = addr;
    char host[INET6_ADDRSTRLEN] = "?";
    if (sa->sa_family == AF_INET6) {
        const struct sockaddr_in6 *v6 = addr;
        inet_ntop(AF_INET6, &v6->sin6_addr, host, sizeof host);
        snprintf(out, size, "[%s]:%u", host, (unsigned)ntohs(v6->sin6_port));
    } else if (sa->sa_family == AF_INET) {
        const struct sockaddr_in *v4 = addr;
        inet_ntop(AF_INET, &v4->sin_addr, host, sizeof host);
        snprintf(out, size, "%s:%u", host, (unsigned)ntohs(v4->sin_port));
    } else {
        snprintf(out, size, "(address family %d)", sa->sa_family);
    }
}

/* One socket bound and listening on `ai`, or -1 with errno set. */
static int listen_on(const struct addrinfo *ai)
{
    int fd = socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0)
        return -1;
    int on = 1;
    /* A restarted daemon must not wait for the old connections' TIME_WAIT. */
    if (setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on) != 0 ||
        bind(fd, ai->ai_addr, ai->ai_addrlen) != 0 || listen(fd, LISTEN_BACKLOG) != 0) {
        int saved = errno;
        close(fd);
        errno = saved;
        return -1;
    }
    return fd;
}

static fc_code describe_bound(fc_listener *l, fc_error *err)
{
    struct sockaddr_storage bound;
    socklen_t len = sizeof bound;
    if (getsockname(l->fd, (struct sockaddr *)&bound, &len) != 0)
        return fc_error_set(err, FC_ERR_IO, "getsockname: %s", strerror(errno));
    fc_format_sockaddr(&bound, l->address, sizeof l->address);
    l->port = ntohs(bound.ss_family == AF_INET6 ? ((struct sockaddr_in6 *)&bound)->sin6_port
                                                : ((struct sockaddr_in *)&bound)->sin_port);
    return FC_OK;
}

fc_code fc_listener_open(const char *host, const char *port, fc_listener *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    out->fd = -1;
    struct addrinfo hints = {0};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE;
    struct addrinfo *list = NULL;
    int rc = getaddrinfo(host, port, &hints, &list);
    if (rc != 0)
        return fc_error_set(err, FC_ERR_IO, "cannot resolve %s:%s: %s", host, port, gai_strerror(rc));
    char tried[512] = "";
    size_t used = 0;
    for (const struct addrinfo *ai = list; ai && out->fd < 0; ai = ai->ai_next) {
        out->fd = listen_on(ai);
        if (out->fd < 0 && used < sizeof tried) {
            char addr[80];
            fc_format_sockaddr(ai->ai_addr, addr, sizeof addr);
            used += (size_t)snprintf(tried + used, sizeof tried - used, "%s%s (%s)", used ? ", " : "", addr,
                                     strerror(errno));
        }
    }
    freeaddrinfo(list);
    if (out->fd < 0)
        return fc_error_set(err, FC_ERR_IO, "cannot listen on %s:%s: %s", host, port, tried);
    fc_code code = describe_bound(out, err);
    if (code != FC_OK)
        fc_listener_close(out);
    return code;
}

/* True when something accepts connections on the socket file at addr. */
static bool socket_file_in_use(const struct sockaddr_un *addr)
{
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return false;
    bool answered = connect(fd, (const struct sockaddr *)addr, sizeof *addr) == 0;
    close(fd);
    return answered;
}

/* Removes a socket file nobody answers on (a daemon that died without cleaning
 * up); anything else at the path is left alone and bind() will say why. */
static fc_code remove_stale_socket(const struct sockaddr_un *addr, fc_error *err)
{
    struct stat st;
    if (lstat(addr->sun_path, &st) != 0 || !S_ISSOCK(st.st_mode))
        return FC_OK;
    if (socket_file_in_use(addr))
        return fc_error_set(err, FC_ERR_IO, "cannot listen on unix:%s: another server answers there",
                            addr->sun_path);
    unlink(addr->sun_path);
    return FC_OK;
}

fc_code fc_listener_open_unix(const char *path, fc_listener *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    out->fd = -1;
    struct sockaddr_un addr = {0};
    addr.sun_family = AF_UNIX;
    if (path[0] == '\0' || strlen(path) >= sizeof addr.sun_path)
        return fc_error_set(err, FC_ERR_USAGE, "--unix path must have 1 to %zu bytes", sizeof addr.sun_path - 1);
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path);
    fc_code code = remove_stale_socket(&addr, err);
    if (code != FC_OK)
        return code;
    struct addrinfo ai = {.ai_family = AF_UNIX, .ai_socktype = SOCK_STREAM,
                          .ai_addr = (struct sockaddr *)&addr, .ai_addrlen = sizeof addr};
    out->fd = listen_on(&ai);
    if (out->fd < 0)
        return fc_error_set(err, FC_ERR_IO, "cannot listen on unix:%s: %s", path, strerror(errno));
    out->is_unix = true;
    snprintf(out->unix_path, sizeof out->unix_path, "%s", path);
    snprintf(out->address, sizeof out->address, "unix:%s", path);
    return FC_OK;
}

/* "unix:PATH" of a bound Unix socket; abstract (leading NUL) and unnamed ones
 * have no file: they are shown as "unix:@NAME" and "unix:(unnamed)". */
static void describe_unix(fc_listener *l, const struct sockaddr_un *addr, socklen_t len)
{
    size_t path_len = len > offsetof(struct sockaddr_un, sun_path) ? len - offsetof(struct sockaddr_un, sun_path) : 0;
    if (path_len == 0) {
        snprintf(l->address, sizeof l->address, "unix:(unnamed)");
    } else if (addr->sun_path[0] == '\0') {
        snprintf(l->address, sizeof l->address, "unix:@%.*s", (int)(path_len - 1), addr->sun_path + 1);
    } else {
        snprintf(l->unix_path, sizeof l->unix_path, "%.*s", (int)strnlen(addr->sun_path, path_len), addr->sun_path);
        snprintf(l->address, sizeof l->address, "unix:%s", l->unix_path);
    }
}

fc_code fc_listener_adopt(int fd, fc_listener *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    out->fd = -1;
    int type = 0, listening = 0;
    socklen_t size = sizeof type;
    struct sockaddr_storage bound;
    socklen_t len = sizeof bound;
    if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &size) != 0 || getsockname(fd, (struct sockaddr *)&bound, &len) != 0)
        return fc_error_set(err, FC_ERR_IO, "inherited descriptor %d is not a socket: %s", fd, strerror(errno));
    size = sizeof listening;
    if (type != SOCK_STREAM || getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &size) != 0 || !listening)
        return fc_error_set(err, FC_ERR_IO, "inherited descriptor %d is not a listening stream socket", fd);
    int flags = fcntl(fd, F_GETFL);
    /* systemd hands sockets over blocking unless NonBlocking=yes; the event loop needs them not to be. */
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0 || fcntl(fd, F_SETFD, FD_CLOEXEC) != 0)
        return fc_error_set(err, FC_ERR_IO, "inherited descriptor %d: fcntl: %s", fd, strerror(errno));
    out->fd = fd;
    out->adopted = true;
    if (bound.ss_family == AF_UNIX) {
        out->is_unix = true;
        describe_unix(out, (const struct sockaddr_un *)&bound, len);
        return FC_OK;
    }
    if (bound.ss_family != AF_INET && bound.ss_family != AF_INET6) {
        out->fd = -1;
        return fc_error_set(err, FC_ERR_IO, "inherited descriptor %d: address family %d is neither TCP nor Unix",
                            fd, bound.ss_family);
    }
    return describe_bound(out, err);
}

void fc_listener_close(fc_listener *l)
{
    if (l->fd >= 0)
        close(l->fd);
    if (l->fd >= 0 && l->is_unix && !l->adopted && l->unix_path[0])
        unlink(l->unix_path);
    l->fd = -1;
}
