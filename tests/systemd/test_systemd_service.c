/* test_systemd_service.c — fluidcastd under a service manager's two protocols,
 * spoken here by the test itself as systemd speaks them:
 *   1. readiness (sd_notify): with NOTIFY_SOCKET set to a datagram socket the
 *      test owns, STATUS= arrives while it starts, READY=1 only once the port
 *      accepts and answers HELLO, STOPPING=1 after SIGTERM, then exit 0;
 *   2. socket activation: a TCP and a Unix listening socket passed as fds 3
 *      and 4 (LISTEN_FDS=2, LISTEN_PID, LISTEN_FDNAMES) are served instead of
 *      binding (--unix naming a folder that does not exist proves it binds
 *      nothing), renders come back through both, the port file names the
 *      passed port, and the Unix socket file, systemd's, is left in place;
 *      a third socket named "metrics" (LISTEN_FDNAMES) serves /readyz;
 *   3. hostile: a UDP socket passed as fd 3 stops startup with exit 1 and a
 *      message naming the descriptor; LISTEN_PID of another process is not
 *      ours, so the daemon binds its own port. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "daemon_process.h"
#include "fc_error.h"
#include "test_scene.h"
#include "test_socket.h"
#include "test_util.h"

enum { MAX_PASSED = 4, STATE_LOG = 8192 };

typedef struct launch {
    const char *const *args;    /* after the binary, NULL-terminated */
    const int *pass_fds;        /* become 3, 4, ...; LISTEN_FDS set when any */
    int pass_count;
    const char *fd_names;       /* LISTEN_FDNAMES, or NULL */
    bool foreign_pid;           /* LISTEN_PID of another process */
    const char *notify_path;    /* NOTIFY_SOCKET, or NULL */
    const char *log_path;       /* stdout and stderr go here, or NULL */
} launch;

static char dir[64];

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

/* In the child: the passed sockets at 3.., the environment, exec. */
static void exec_daemon(const launch *l, pid_t test_pid)
{
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != test_pid)
        _exit(127);
    if (l->log_path) {
        int log = open(l->log_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (log < 0 || dup2(log, 1) < 0 || dup2(log, 2) < 0)
            _exit(127);
    }
    int high[MAX_PASSED];
    /* Moved out of the way first, so dup2 to 3.. never overwrites one still to come. */
    for (int i = 0; i < l->pass_count; i++)
        high[i] = fcntl(l->pass_fds[i], F_DUPFD, 100);
    for (int i = 0; i < l->pass_count; i++)
        if (high[i] < 0 || dup2(high[i], 3 + i) < 0)
            _exit(127);
    char number[32];
    if (l->pass_count > 0) {
        snprintf(number, sizeof number, "%d", l->pass_count);
        setenv("LISTEN_FDS", number, 1);
        snprintf(number, sizeof number, "%d", l->foreign_pid ? (int)getppid() : (int)getpid());
        setenv("LISTEN_PID", number, 1);
        if (l->fd_names)
            setenv("LISTEN_FDNAMES", l->fd_names, 1);
    }
    if (l->notify_path)
        setenv("NOTIFY_SOCKET", l->notify_path, 1);
    const char *argv[32] = {fc_test_daemon_path()};
    int argc = 1;
    for (int i = 0; l->args[i] && argc < 31; i++)
        argv[argc++] = l->args[i];
    argv[argc] = NULL;
    execv(argv[0], (char *const *)argv);
    _exit(127);
}

static pid_t start(const launch *l)
{
    pid_t test_pid = getpid();
    pid_t pid = fork();
    if (pid == 0)
        exec_daemon(l, test_pid);
    return pid;
}

/* A datagram socket bound at path, as systemd's notification socket. */
static int open_notify_socket(const char *path)
{
    int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path);
    if (fd < 0 || bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        CHECK_MSG(0, "cannot bind the notification socket %s: %s", path, strerror(errno));
        return -1;
    }
    return fd;
}

/* True when `state` (a datagram of "KEY=VALUE" lines) has the line `line`. */
static bool has_line(const char *state, const char *line)
{
    size_t n = strlen(line);
    for (const char *p = state; (p = strstr(p, line)) != NULL; p += n)
        if ((p == state || p[-1] == '\n') && (p[n] == '\0' || p[n] == '\n'))
            return true;
    return false;
}

/* Reads datagrams until one has the line `want`, appending all to log;
 * that datagram is left in `last`. False on timeout. */
static bool wait_for_state(int fd, const char *want, int timeout_ms, char *log, char *last, size_t size)
{
    double deadline = now_ms() + timeout_ms;
    while (now_ms() < deadline) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        if (poll(&p, 1, 100) <= 0)
            continue;
        ssize_t n = recv(fd, last, size - 1, 0);
        if (n < 0)
            continue;
        last[n] = '\0';
        size_t used = strlen(log);
        snprintf(log + used, STATE_LOG - used, "%s\n---\n", last);
        if (has_line(last, want))
            return true;
    }
    return false;
}

static int wait_exit(pid_t pid, int timeout_ms)
{
    int status;
    for (double deadline = now_ms() + timeout_ms; now_ms() < deadline;) {
        if (waitpid(pid, &status, WNOHANG) == pid)
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        usleep(20000);
    }
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
    return -1;
}

static unsigned read_port_file(const char *path)
{
    unsigned port = 0;
    FILE *f = fopen(path, "r");
    if (f && fscanf(f, "%u", &port) != 1)
        port = 0;
    if (f)
        fclose(f);
    return port;
}

/* HELLO and one small render on a connected socket; true when an IMAGE comes back. */
static bool renders(int fd, const char *where)
{
    fc_error err;
    fc_welcome welcome;
    fc_test_message reply = {0};
    fc_render_request request = {FC_FORMAT_PNG, 90, FC_AOV_COLOR};
    if (fc_test_handshake(fd, 1, &welcome, &err) != FC_OK ||
        fc_test_render(fd, 2, 32, 24, &request, &reply, &err) != FC_OK) {
        CHECK_MSG(0, "%s: %s", where, err.message);
        return false;
    }
    bool image = reply.header.type == FC_MSG_IMAGE;
    CHECK_MSG(image, "%s: reply type %u, expected IMAGE", where, (unsigned)reply.header.type);
    fc_test_message_free(&reply);
    return image;
}

static int connect_unix(const char *path)
{
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path);
    if (fd >= 0 && connect(fd, (struct sockaddr *)&addr, sizeof addr) == 0)
        return fd;
    CHECK_MSG(0, "connect unix:%s: %s", path, strerror(errno));
    if (fd >= 0)
        close(fd);
    return -1;
}

/* The status code of GET path on 127.0.0.1:port, 0 without an answer. */
static int http_status(uint16_t port, const char *path)
{
    int fd = -1, status = 0;
    fc_error err;
    char request[128], answer[256] = "";
    snprintf(request, sizeof request, "GET %s HTTP/1.0\r\n\r\n", path);
    if (fc_test_connect(port, &fd, &err) != FC_OK)
        return 0;
    struct pollfd p = {.fd = fd, .events = POLLIN};
    if (fc_test_send(fd, request, strlen(request), &err) == FC_OK && poll(&p, 1, 10000) == 1 &&
        recv(fd, answer, sizeof answer - 1, 0) > 0)
        sscanf(answer, "HTTP/1.%*d %d", &status);
    close(fd);
    return status;
}

static void test_readiness(void)
{
    char notify[96], port_file[128], log[STATE_LOG] = "", last[1024];
    snprintf(notify, sizeof notify, "%s/notify", dir);
    snprintf(port_file, sizeof port_file, "%s/port", dir);
    int nfd = open_notify_socket(notify);
    if (nfd < 0)
        return;
    const char *const args[] = {"--listen", "127.0.0.1:0", "--port-file", port_file, "--gpu", "software", NULL};
    launch l = {.args = args, .notify_path = notify};
    pid_t pid = start(&l);
    bool ready = wait_for_state(nfd, "READY=1", FC_TEST_DAEMON_START_TIMEOUT_MS, log, last, sizeof last);
    CHECK_MSG(ready, "no READY=1 within %d ms; got:\n%s", FC_TEST_DAEMON_START_TIMEOUT_MS, log);
    if (ready) {
        /* READY=1 has come: the port must already accept and answer. */
        unsigned port = read_port_file(port_file);
        CHECK_MSG(port > 0, "READY=1 before the port file was written");
        int fd = -1;
        fc_error err;
        CHECK_MSG(port > 0 && fc_test_connect((uint16_t)port, &fd, &err) == FC_OK, "READY=1 but connect fails");
        if (fd >= 0) {
            renders(fd, "after READY=1");
            close(fd);
        }
        CHECK_MSG(strstr(log, "STATUS=starting") != NULL, "no STATUS= while starting:\n%s", log);
        CHECK_MSG(strstr(last, "STATUS=serving on 127.0.0.1:") != NULL && strstr(last, "llvmpipe"),
                  "READY=1 without a STATUS= naming the address and renderer:\n%s", last);
    }
    kill(pid, SIGTERM);
    bool stopping = wait_for_state(nfd, "STOPPING=1", 10000, log, last, sizeof last);
    CHECK_MSG(stopping, "no STOPPING=1 after SIGTERM; got:\n%s", log);
    CHECK_MSG(strstr(last, "STATUS=stopping") != NULL, "STOPPING=1 without a STATUS=:\n%s", last);
    int status = wait_exit(pid, FC_TEST_DAEMON_STOP_TIMEOUT_MS);
    CHECK_MSG(status == 0, "exit status %d after SIGTERM, expected 0", status);
    close(nfd);
    unlink(notify);
    unlink(port_file);
}

/* A TCP socket listening on 127.0.0.1 (any port): *port. */
static int listen_tcp(uint16_t *port)
{
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof addr;
    if (fd < 0 || bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0 || listen(fd, 16) != 0 ||
        getsockname(fd, (struct sockaddr *)&addr, &len) != 0) {
        CHECK_MSG(0, "cannot listen on TCP: %s", strerror(errno));
        return -1;
    }
    *port = ntohs(addr.sin_port);
    return fd;
}

static int listen_unix(const char *path)
{
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path);
    if (fd < 0 || bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0 || listen(fd, 16) != 0) {
        CHECK_MSG(0, "cannot listen on unix:%s: %s", path, strerror(errno));
        return -1;
    }
    return fd;
}

static void test_activation(void)
{
    char notify[96], port_file[128], sock[96], log[STATE_LOG] = "", last[1024];
    snprintf(notify, sizeof notify, "%s/notify", dir);
    snprintf(port_file, sizeof port_file, "%s/port", dir);
    snprintf(sock, sizeof sock, "%s/fc.sock", dir);
    uint16_t port = 0;
    int nfd = open_notify_socket(notify);
    uint16_t metrics_port = 0;
    int fds[3] = {listen_tcp(&port), listen_unix(sock), listen_tcp(&metrics_port)};
    if (nfd < 0 || fds[0] < 0 || fds[1] < 0 || fds[2] < 0)
        return;
    /* Were --unix bound, it would fail: the folder does not exist. */
    const char *const args[] = {"--unix", "/nonexistent/fluidcast.sock", "--port-file", port_file,
                                "--gpu", "software", NULL};
    launch l = {.args = args, .pass_fds = fds, .pass_count = 3, .fd_names = "render:render:metrics",
                .notify_path = notify};
    pid_t pid = start(&l);
    bool ready = wait_for_state(nfd, "READY=1", FC_TEST_DAEMON_START_TIMEOUT_MS, log, last, sizeof last);
    CHECK_MSG(ready, "socket activation: no READY=1; got:\n%s", log);
    if (ready) {
        CHECK_MSG(read_port_file(port_file) == port, "port file says %u, the passed socket is %u",
                  read_port_file(port_file), (unsigned)port);
        CHECK_MSG(strstr(last, sock) != NULL, "STATUS= does not name the passed Unix socket:\n%s", last);
        int fd = -1;
        fc_error err;
        CHECK_MSG(fc_test_connect(port, &fd, &err) == FC_OK, "%s", err.message);
        if (fd >= 0) {
            renders(fd, "through the passed TCP socket");
            close(fd);
        }
        fd = connect_unix(sock);
        if (fd >= 0) {
            renders(fd, "through the passed Unix socket");
            close(fd);
        }
        CHECK_MSG(http_status(metrics_port, "/readyz") == 200, "the passed 'metrics' socket does not serve /readyz");
    }
    kill(pid, SIGTERM);
    CHECK_MSG(wait_exit(pid, FC_TEST_DAEMON_STOP_TIMEOUT_MS) == 0, "socket activation: no clean exit");
    struct stat st;
    CHECK_MSG(stat(sock, &st) == 0 && S_ISSOCK(st.st_mode),
              "the daemon removed the Unix socket file the service manager owns");
    close(fds[0]);
    close(fds[1]);
    close(fds[2]);
    close(nfd);
    unlink(sock);
    unlink(notify);
    unlink(port_file);
}

static bool file_contains(const char *path, const char *text)
{
    char buf[16384];
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f)
        fclose(f);
    buf[n] = '\0';
    return strstr(buf, text) != NULL;
}

static void test_hostile(void)
{
    char log_path[128], port_file[128];
    snprintf(log_path, sizeof log_path, "%s/daemon.log", dir);
    snprintf(port_file, sizeof port_file, "%s/port", dir);
    int udp = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    const char *const args[] = {"--listen", "127.0.0.1:0", "--port-file", port_file, "--gpu", "software", NULL};
    launch l = {.args = args, .pass_fds = &udp, .pass_count = 1, .log_path = log_path};
    int status = wait_exit(start(&l), FC_TEST_DAEMON_START_TIMEOUT_MS);
    CHECK_MSG(status == 1, "a UDP socket passed as fd 3: exit status %d, expected 1", status);
    CHECK_MSG(file_contains(log_path, "descriptor 3 is not a listening TCP or Unix stream socket"),
              "the log does not say what is wrong with descriptor 3");

    /* LISTEN_PID names another process: the sockets are not for this one. */
    l.foreign_pid = true;
    pid_t pid = start(&l);
    unsigned port = 0;
    for (double deadline = now_ms() + FC_TEST_DAEMON_START_TIMEOUT_MS; port == 0 && now_ms() < deadline;)
        if ((port = read_port_file(port_file)) == 0)
            usleep(20000);
    CHECK_MSG(port > 0, "with another process's LISTEN_PID the daemon did not bind its own port");
    kill(pid, SIGTERM);
    CHECK_MSG(wait_exit(pid, FC_TEST_DAEMON_STOP_TIMEOUT_MS) == 0, "no clean exit");
    close(udp);
    unlink(log_path);
    unlink(port_file);
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    snprintf(dir, sizeof dir, "/tmp/fc-systemd-XXXXXX");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_readiness();
    test_activation();
    test_hostile();
    rmdir(dir);
    return test_result();
}
