/* test_metrics.c — fluidcastd --metrics-listen against real HTTP requests over
 * a socket (a few lines of HTTP/1.0 here, no HTTP library):
 *   - /healthz 200, /readyz 200 once serving; /metrics in Prometheus' text
 *     format, checked by `promtool check metrics` (skipped, exit 77 after all
 *     other checks, when promtool is not installed);
 *   - counters move with renders: frames rendered, render and encode histograms
 *     (buckets cumulative, +Inf == _count == renders), bytes both ways, an
 *     ERROR LIMIT counted, build_info naming llvmpipe;
 *   - /readyz 503 during the SIGTERM drain (a 2048x2048 RAW reply the client
 *     does not read yet keeps the daemon draining) while /healthz stays 200;
 *     the client then gets its whole image and the daemon exits 0;
 *   - hostile: unknown paths 404, POST/PUT/DELETE 405 with Allow, a garbage
 *     request line 400, and the daemon serves on; a busy metrics port stops
 *     startup with exit 1 and a message naming it. */
#define _GNU_SOURCE
#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "daemon_process.h"
#include "fc_error.h"
#include "test_scene.h"
#include "test_socket.h"
#include "test_util.h"

enum { HTTP_TIMEOUT_MS = 10000, MAX_RESPONSE = 1 << 20 };

typedef struct http_response {
    int status;          /* 0: no answer */
    char *head;          /* status line and headers */
    char *body;
} http_response;

static void http_free(http_response *r)
{
    free(r->head);
    r->head = r->body = NULL;
}

/* Sends `request` as is and reads the answer until the server closes. */
static http_response http_raw(uint16_t port, const char *request)
{
    http_response r = {0};
    int fd = -1;
    fc_error err;
    if (fc_test_connect(port, &fd, &err) != FC_OK || fc_test_send(fd, request, strlen(request), &err) != FC_OK) {
        if (fd >= 0)
            close(fd);
        return r;
    }
    char *buf = malloc(MAX_RESPONSE + 1);
    size_t got = 0;
    for (;;) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        if (poll(&p, 1, HTTP_TIMEOUT_MS) <= 0)
            break;
        ssize_t n = recv(fd, buf + got, MAX_RESPONSE - got, 0);
        if (n <= 0)
            break;
        got += (size_t)n;
    }
    close(fd);
    buf[got] = '\0';
    char *end = strstr(buf, "\r\n\r\n");
    if (sscanf(buf, "HTTP/1.%*d %d", &r.status) != 1 || !end) {
        free(buf);
        r.status = 0;
        return r;
    }
    *end = '\0';
    r.head = buf;
    r.body = end + 4;
    return r;
}

static http_response http(uint16_t port, const char *method, const char *path)
{
    char request[256];
    snprintf(request, sizeof request, "%s %s HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n", method, path);
    return http_raw(port, request);
}

static int http_status(uint16_t port, const char *method, const char *path)
{
    http_response r = http(port, method, path);
    int status = r.status;
    http_free(&r);
    return status;
}

/* The value of the sample `series` (name with labels, exactly as written), or -1. */
static double sample(const char *body, const char *series)
{
    size_t n = strlen(series);
    for (const char *p = body; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
        if (strncmp(p, series, n) == 0 && p[n] == ' ')
            return strtod(p + n + 1, NULL);
    return -1.0;
}

/* A free port now (bound, read, closed): the daemon binds it right after. */
static uint16_t free_port(void)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof addr;
    bind(fd, (struct sockaddr *)&addr, sizeof addr);
    getsockname(fd, (struct sockaddr *)&addr, &len);
    close(fd);
    return ntohs(addr.sin_port);
}

static bool render_once(uint16_t port, uint32_t width, uint32_t height, uint16_t *type)
{
    int fd = -1;
    fc_error err;
    fc_welcome welcome;
    fc_test_message reply = {0};
    fc_render_request request = {FC_FORMAT_PNG, 90, FC_AOV_COLOR};
    bool ok = fc_test_connect(port, &fd, &err) == FC_OK && fc_test_handshake(fd, 1, &welcome, &err) == FC_OK &&
              fc_test_render(fd, 2, width, height, &request, &reply, &err) == FC_OK;
    CHECK_MSG(ok, "render %ux%u: %s", width, height, err.message);
    *type = ok ? reply.header.type : 0;
    fc_test_message_free(&reply);
    if (fd >= 0)
        close(fd);
    return ok;
}

/* Buckets of `name` never decrease and the +Inf one equals _count. */
static void check_histogram(const char *body, const char *name, double expected_count)
{
    char series[128];
    double previous = 0.0;
    int buckets = 0;
    for (const char *p = body; (p = strstr(p, name)) != NULL; p++) {
        snprintf(series, sizeof series, "%s_bucket{le=\"", name);
        if (strncmp(p, series, strlen(series)) != 0 || (p != body && p[-1] != '\n'))
            continue;
        double v = strtod(strchr(p, ' ') + 1, NULL);
        CHECK_MSG(v >= previous, "%s: bucket %d has %g after %g: not cumulative", name, buckets, v, previous);
        previous = v;
        buckets++;
    }
    snprintf(series, sizeof series, "%s_bucket{le=\"+Inf\"}", name);
    double inf = sample(body, series);
    snprintf(series, sizeof series, "%s_count", name);
    double count = sample(body, series);
    CHECK_MSG(buckets >= 2 && inf == count && count == expected_count,
              "%s: %d buckets, +Inf %g, _count %g, expected %g", name, buckets, inf, count, expected_count);
    CHECK_MSG(previous == inf, "%s: the last bucket read is not +Inf", name);
}

/* promtool check metrics on the body: 0 passes, 77 when promtool is missing. */
static int promtool_check(const char *body)
{
    if (system("command -v promtool > /dev/null 2>&1") != 0)
        return 77;
    char path[] = "/tmp/fc-metrics-XXXXXX";
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f)
        return 1;
    fputs(body, f);
    fclose(f);
    char command[128];
    snprintf(command, sizeof command, "promtool check metrics < %s", path);
    int status = system(command);
    unlink(path);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

static int check_metrics_after_renders(uint16_t port, uint16_t metrics_port)
{
    http_response before = http(metrics_port, "GET", "/metrics");
    CHECK_MSG(before.status == 200, "/metrics: status %d", before.status);
    double rendered0 = before.body ? sample(before.body, "fluidcast_frames_rendered_total") : -1;
    CHECK_MSG(rendered0 == 0, "frames rendered before any render: %g", rendered0);
    http_free(&before);

    uint16_t type = 0;
    for (int i = 0; i < 3; i++) {
        render_once(port, 64, 48, &type);
        CHECK_MSG(type == FC_MSG_IMAGE, "render %d: reply type %u", i, (unsigned)type);
    }
    render_once(port, 4096, 4096, &type);   /* beyond --max-image 2048x2048 */
    CHECK_MSG(type == FC_MSG_ERROR, "a render beyond --max-image: reply type %u, expected ERROR", (unsigned)type);

    http_response r = http(metrics_port, "GET", "/metrics");
    CHECK_MSG(r.status == 200 && r.head && strstr(r.head, "text/plain; version=0.0.4"),
              "/metrics: status %d, head:\n%s", r.status, r.head ? r.head : "");
    if (!r.body)
        return 1;
    CHECK_MSG(sample(r.body, "fluidcast_frames_rendered_total") == 3, "frames rendered: %g, expected 3",
              sample(r.body, "fluidcast_frames_rendered_total"));
    check_histogram(r.body, "fluidcast_render_seconds", 3);
    check_histogram(r.body, "fluidcast_encode_seconds", 3);
    CHECK_MSG(sample(r.body, "fluidcast_render_seconds_sum") > 0, "render seconds sum is 0");
    CHECK_MSG(sample(r.body, "fluidcast_limit_rejections_total") == 1, "limit rejections: %g, expected 1",
              sample(r.body, "fluidcast_limit_rejections_total"));
    CHECK_MSG(sample(r.body, "fluidcast_connections_accepted_total") == 4, "connections accepted: %g, expected 4",
              sample(r.body, "fluidcast_connections_accepted_total"));
    CHECK_MSG(sample(r.body, "fluidcast_received_bytes_total") > 4 * 16, "bytes received: %g",
              sample(r.body, "fluidcast_received_bytes_total"));
    CHECK_MSG(sample(r.body, "fluidcast_sent_bytes_total") > 3 * 100, "bytes sent: %g",
              sample(r.body, "fluidcast_sent_bytes_total"));
    CHECK_MSG(sample(r.body, "fluidcast_frames_dropped_total{reason=\"render_failed\"}") == 0, "render failures");
    CHECK_MSG(sample(r.body, "fluidcast_ready") == 1, "fluidcast_ready is not 1 while serving");
    CHECK_MSG(strstr(r.body, "fluidcast_build_info{version=\"0.1.0\",renderer=\"llvmpipe") != NULL,
              "build_info without the version and renderer");
    int promtool = promtool_check(r.body);
    CHECK_MSG(promtool == 0 || promtool == 77, "promtool check metrics failed (exit %d) on:\n%s", promtool, r.body);
    http_free(&r);
    return promtool;
}

static void check_hostile(uint16_t port, uint16_t metrics_port)
{
    CHECK_CODE(http_status(metrics_port, "GET", "/"), 404);
    CHECK_CODE(http_status(metrics_port, "GET", "/metrics/extra"), 404);
    CHECK_CODE(http_status(metrics_port, "GET", "/../etc/passwd"), 404);
    static const char *const methods[] = {"POST", "PUT", "DELETE", "OPTIONS"};
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++) {
        http_response r = http(metrics_port, methods[i], "/metrics");
        CHECK_MSG(r.status == 405 && r.head && strstr(r.head, "Allow: GET, HEAD"), "%s /metrics: status %d",
                  methods[i], r.status);
        http_free(&r);
    }
    http_response head = http(metrics_port, "HEAD", "/healthz");
    CHECK_MSG(head.status == 200 && head.body && head.body[0] == '\0', "HEAD /healthz: status %d or a body",
              head.status);
    http_free(&head);
    http_response bad = http_raw(metrics_port, "GARBAGE\r\n\r\n");
    CHECK_MSG(bad.status == 400 || bad.status == 0, "a garbage request line: status %d", bad.status);
    http_free(&bad);
    /* Still serving, on both ports. */
    CHECK_CODE(http_status(metrics_port, "GET", "/healthz"), 200);
    uint16_t type = 0;
    render_once(port, 16, 16, &type);
    CHECK_MSG(type == FC_MSG_IMAGE, "the render port after hostile HTTP: reply type %u", (unsigned)type);
}

/* SIGTERM while a large reply waits unread: /readyz 503, /healthz 200, then
 * the client reads its image and the daemon exits 0. */
static void check_drain(fc_test_daemon *d, uint16_t metrics_port)
{
    int fd = -1;
    fc_error err;
    fc_welcome welcome;
    CHECK_MSG(fc_test_connect(d->port, &fd, &err) == FC_OK && fc_test_handshake(fd, 1, &welcome, &err) == FC_OK,
              "%s", err.message);
    int small = 64 * 1024;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    fc_buf out;
    fc_buf_init(&out);
    fc_render_request request = {FC_FORMAT_RAW, 0, FC_AOV_COLOR};
    CHECK(fc_test_write_render_sequence(&out, 7, 2048, 2048, &request, &err) == FC_OK &&
          fc_test_send(fd, out.data, out.len, &err) == FC_OK);
    fc_buf_free(&out);
    /* The first bytes of the 16 MiB reply: it is rendered and queued. */
    struct pollfd p = {.fd = fd, .events = POLLIN};
    CHECK_MSG(poll(&p, 1, 60000) == 1, "no reply to the large render within 60 s");
    kill(d->pid, SIGTERM);
    int ready = 0, healthy = 0;
    /* Up to 30 s for the signal to be handled: a wait, generous for a loaded machine, not a timing. */
    for (int i = 0; i < 1500 && ready != 503; i++) {
        ready = http_status(metrics_port, "GET", "/readyz");
        healthy = http_status(metrics_port, "GET", "/healthz");
        if (ready != 503)
            usleep(20000);
    }
    CHECK_MSG(ready == 503, "/readyz during the drain: %d, expected 503", ready);
    CHECK_MSG(healthy == 200, "/healthz during the drain: %d, expected 200", healthy);
    http_response m = http(metrics_port, "GET", "/metrics");
    CHECK_MSG(m.body && sample(m.body, "fluidcast_ready") == 0, "fluidcast_ready is not 0 while draining");
    http_free(&m);
    fc_test_message reply = {0};
    CHECK_MSG(fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &reply, &err) == FC_OK &&
                  reply.header.type == FC_MSG_IMAGE,
              "the image in flight was not delivered during the drain: %s", err.message);
    fc_test_message_free(&reply);
    close(fd);
    CHECK_MSG(fc_test_daemon_stop(d, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
}

static void check_busy_port(void)
{
    int holder = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof addr;
    if (bind(holder, (struct sockaddr *)&addr, sizeof addr) != 0 || listen(holder, 1) != 0 ||
        getsockname(holder, (struct sockaddr *)&addr, &len) != 0) {
        CHECK_MSG(0, "cannot hold a port: %s", strerror(errno));
        return;
    }
    char log_path[] = "/tmp/fc-metrics-log-XXXXXX";
    int log = mkstemp(log_path);
    char busy[32];
    snprintf(busy, sizeof busy, "%u", (unsigned)ntohs(addr.sin_port));
    pid_t pid = fork();
    if (pid == 0) {
        dup2(log, 2);
        dup2(log, 1);
        execl(fc_test_daemon_path(), fc_test_daemon_path(), "--gpu", "software", "--listen", "127.0.0.1:0",
              "--metrics-listen", busy, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 1, "a busy metrics port: exit status 0x%x, expected 1",
              status);
    char text[4096] = "";
    ssize_t n = pread(log, text, sizeof text - 1, 0);
    text[n > 0 ? n : 0] = '\0';
    char expected[96];
    snprintf(expected, sizeof expected, "--metrics-listen: cannot listen on 127.0.0.1:%s", busy);
    CHECK_MSG(strstr(text, expected) && strstr(text, "Address already in use"),
              "the error does not name the busy metrics port:\n%s", text);
    close(log);
    unlink(log_path);
    close(holder);
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    check_busy_port();
    uint16_t metrics_port = free_port();
    char metrics_arg[32];
    snprintf(metrics_arg, sizeof metrics_arg, "127.0.0.1:%u", (unsigned)metrics_port);
    const char *const args[] = {"--metrics-listen", metrics_arg, "--max-image", "2048x2048", NULL};
    fc_test_daemon d;
    fc_error err;
    if (fc_test_daemon_start(&d, args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        CHECK_MSG(0, "cannot start the daemon: %s", err.message);
        return test_result();
    }
    http_response health = http(metrics_port, "GET", "/healthz");
    CHECK_MSG(health.status == 200 && health.body && strcmp(health.body, "ok\n") == 0, "/healthz: %d",
              health.status);
    http_free(&health);
    CHECK_CODE(http_status(metrics_port, "GET", "/readyz"), 200);
    int promtool = check_metrics_after_renders(d.port, metrics_port);
    check_hostile(d.port, metrics_port);
    check_drain(&d, metrics_port);
    int result = test_result();
    if (result == 0 && promtool == 77) {
        printf("SKIP: promtool not installed (apt-get install prometheus); every other check passed\n");
        return 77;
    }
    return result;
}
