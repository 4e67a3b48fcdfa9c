/* test_auth_daemon.c — the real fluidcastd with a token file and tiny limits:
 * the right token is served end to end (raw HELLO, libfluidcast, the CLI with
 * FLUIDCAST_TOKEN or --token-file); a missing or wrong one, or anything sent
 * before HELLO, gets ERROR UNAUTHORIZED and a closed connection; a client
 * beyond --max-connections gets LIMIT while the others are served; a client
 * stalled mid-message or silent is closed after its timeout while another is
 * served. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "support/daemon_process.h"
#include "support/test_scene.h"
#include "test_ball.h"
#include "test_util.h"

#define TOKEN "correct horse battery staple"
#define MAX_CONNECTIONS 3
#define READ_TIMEOUT_MS 300
#define IDLE_TIMEOUT_MS 4000
/* Exit status of the CLI when the server answers with an error (cli_report.h). */
#define CLI_EXIT_SERVER 5

typedef struct test_env {
    char dir[64];
    char token_file[96];
    char server[32];
    uint16_t port;
} test_env;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int open_connection(uint16_t port)
{
    int fd = -1;
    fc_error err;
    CHECK_MSG(fc_test_connect(port, &fd, &err) == FC_OK, "%s", err.message);
    return fd;
}

static void send_hello(int fd, uint32_t request_id, const char *token)
{
    fc_hello hello = {.version_min = 1, .version_max = 1, .client_name = "test_auth"};
    snprintf(hello.token, sizeof hello.token, "%s", token);
    fc_buf b;
    fc_error err;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_hello(&b, request_id, &hello, &err), FC_OK);
    CHECK_MSG(fc_test_send(fd, b.data, b.len, &err) == FC_OK, "%s", err.message);
    fc_buf_free(&b);
}

/* A connection that presented the right token; *reply is the daemon's answer
 * (WELCOME, or ERROR LIMIT beyond --max-connections). -1 when there is none. */
static int hello_connection(uint16_t port, fc_test_message *reply)
{
    int fd = open_connection(port);
    if (fd < 0)
        return -1;
    send_hello(fd, 1, TOKEN);
    fc_error err;
    if (fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, reply, &err) != FC_OK) {
        CHECK_MSG(0, "no answer to HELLO: %s", err.message);
        close(fd);
        return -1;
    }
    return fd;
}

/* A connection that presented the right token and got WELCOME; -1 on failure. */
static int authenticated_connection(uint16_t port)
{
    fc_test_message reply;
    int fd = hello_connection(port, &reply);
    if (fd < 0)
        return -1;
    CHECK_MSG(reply.header.type == FC_MSG_WELCOME && reply.header.request_id == 1, "type %u",
              reply.header.type);
    fc_test_message_free(&reply);
    return fd;
}

/* n authenticated connections in fds. The daemon notices the connections
 * earlier tests closed only when it next reads them; until then they count
 * against --max-connections and a new one gets ERROR LIMIT. So all n are
 * tried again, a little later, until all get WELCOME (or the I/O timeout). */
static bool hold_connections(uint16_t port, int n, int *fds)
{
    struct timespec pause = {0, 20 * 1000 * 1000};
    for (double deadline = now_ms() + FC_TEST_IO_TIMEOUT_MS; now_ms() < deadline; nanosleep(&pause, NULL)) {
        int welcomed = 0;
        for (int i = 0; i < n; i++) {
            fc_test_message reply;
            fds[i] = hello_connection(port, &reply);
            if (fds[i] < 0)
                return false;
            welcomed += reply.header.type == FC_MSG_WELCOME;
            fc_test_message_free(&reply);
        }
        if (welcomed == n)
            return true;
        for (int i = 0; i < n; i++)
            close(fds[i]);
    }
    CHECK_MSG(0, "%d connections were not all welcomed within %d ms", n, FC_TEST_IO_TIMEOUT_MS);
    return false;
}

static void expect_error(int fd, uint32_t request_id, fc_code code)
{
    uint32_t got_id = 0;
    fc_error remote = {0}, err;
    if (fc_test_read_error(fd, &got_id, &remote, &err) != FC_OK) {
        CHECK_MSG(0, "expected ERROR %d for request %u: %s", code, request_id, err.message);
        return;
    }
    CHECK_MSG(got_id == request_id, "ERROR answers request %u, expected %u", got_id, request_id);
    CHECK_MSG(remote.code == code, "ERROR code %d (%s), expected %d", remote.code, remote.message, code);
}

/* ERROR `code` for request 0 whose message says `why`. */
static void expect_error_saying(int fd, fc_code code, const char *why)
{
    uint32_t got_id = 0;
    fc_error remote = {0}, err;
    if (fc_test_read_error(fd, &got_id, &remote, &err) != FC_OK) {
        CHECK_MSG(0, "expected ERROR %d (%s): %s", code, why, err.message);
        return;
    }
    CHECK_MSG(got_id == 0 && remote.code == code && strstr(remote.message, why),
              "ERROR %d \"%s\" for request %u, expected %d saying \"%s\"", remote.code, remote.message, got_id, code,
              why);
}

static void expect_closed(int fd)
{
    fc_error err;
    CHECK_MSG(fc_test_expect_closed(fd, FC_TEST_IO_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
}

static void expect_renders(int fd, uint32_t request_id)
{
    fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
    fc_test_message reply;
    fc_error err;
    if (fc_test_render(fd, request_id, 32, 24, &request, &reply, &err) != FC_OK) {
        CHECK_MSG(0, "render %u: %s", request_id, err.message);
        return;
    }
    CHECK_MSG(reply.header.type == FC_MSG_IMAGE && reply.header.request_id == request_id + 2,
              "render %u answered by type %u", request_id, reply.header.type);
    fc_test_message_free(&reply);
}

/* HELLO with `token` is refused with UNAUTHORIZED echoing its id, then closed. */
static void expect_refused_hello(uint16_t port, const char *token)
{
    int fd = open_connection(port);
    if (fd < 0)
        return;
    send_hello(fd, 5, token);
    expect_error(fd, 5, FC_ERR_UNAUTHORIZED);
    expect_closed(fd);
    close(fd);
}

static void test_raw_tokens(uint16_t port)
{
    int fd = authenticated_connection(port);
    if (fd >= 0)
        expect_renders(fd, 10);
    close(fd);
    expect_refused_hello(port, "");                              /* no token field at all */
    expect_refused_hello(port, "correct horse battery stapler"); /* one byte longer */
    expect_refused_hello(port, "correct horse battery stapl");   /* a prefix */
    expect_refused_hello(port, "correct horse battery staplE");  /* same length, last byte differs */
}

/* Before authentication even protocol errors are answered with UNAUTHORIZED only. */
static void test_nothing_before_hello(uint16_t port)
{
    int fd = open_connection(port);
    fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
    fc_buf b;
    fc_error err;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_render(&b, 3, &request, &err), FC_OK);
    CHECK_MSG(fc_test_send(fd, b.data, b.len, &err) == FC_OK, "%s", err.message);
    expect_error(fd, 3, FC_ERR_UNAUTHORIZED);
    expect_closed(fd);
    close(fd);
    fd = open_connection(port);
    static const char garbage[] = "GET / HTTP/1.1\r\n\r\n";
    CHECK_MSG(fc_test_send(fd, garbage, sizeof garbage - 1, &err) == FC_OK, "%s", err.message);
    expect_error(fd, 0, FC_ERR_UNAUTHORIZED);
    expect_closed(fd);
    close(fd);
    fc_buf_free(&b);
}

static void test_library(const test_env *env)
{
    fc_connect_options options = {.client_name = "test_auth", .token = "wrong"};
    fc_client *c = NULL;
    fc_error err;
    CHECK_CODE(fc_client_connect(env->server, &options, &c, &err), FC_ERR_UNAUTHORIZED);
    CHECK(c == NULL);
    options.token = NULL;
    CHECK_CODE(fc_client_connect(env->server, &options, &c, &err), FC_ERR_UNAUTHORIZED);
    options.token = TOKEN;
    CHECK_CODE(fc_client_connect(env->server, &options, &c, &err), FC_OK);
    fc_server_info info;
    if (c) {
        fc_client_server_info(c, &info);
        CHECK(info.protocol_version == 1);
        fc_client_close(c);
    }
}

static bool is_png(const char *path)
{
    size_t size = 0;
    uint8_t *bytes = read_whole_file(path, &size);
    bool png = bytes && size > 8 && memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
    free(bytes);
    return png;
}

static void test_cli(const test_env *env)
{
    char particles[128], image[128];
    snprintf(particles, sizeof particles, "%s/ball.f32", env->dir);
    snprintf(image, sizeof image, "%s/ball.png", env->dir);
    fc_frame ball = {0};
    CHECK(test_ball_frame(&ball, NULL) == FC_OK && test_write_f32(&ball, particles));
    fc_frame_free(&ball);
    cli_result r;
    const char *const args[] = {"snapshot", particles, "-o", image, "--server", env->server, "--size", "32x24",
                                "--radius", "0.05", NULL};
    unsetenv("FLUIDCAST_TOKEN");
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, &r);
    CHECK_MSG(r.status == CLI_EXIT_SERVER && strstr(r.err, "authentication required") != NULL, "status %d: %s", r.status,
              r.err);
    setenv("FLUIDCAST_TOKEN", TOKEN, 1);
    cli_run(FLUIDCAST_CLI_PATH, env->dir, args, &r);
    CHECK_MSG(r.status == 0, "status %d: %s", r.status, r.err);
    CHECK(is_png(image));
    unlink(image);
    /* --token-file wins over a wrong FLUIDCAST_TOKEN, and works after the subcommand's arguments. */
    setenv("FLUIDCAST_TOKEN", "wrong", 1);
    const char *const file_args[] = {"snapshot", particles, "-o", image, "--server", env->server, "--size",
                                     "32x24", "--radius", "0.05", "--token-file", env->token_file, NULL};
    cli_run(FLUIDCAST_CLI_PATH, env->dir, file_args, &r);
    CHECK_MSG(r.status == 0, "status %d: %s", r.status, r.err);
    CHECK(is_png(image));
    unsetenv("FLUIDCAST_TOKEN");
}

static void test_max_connections(uint16_t port)
{
    int held[MAX_CONNECTIONS];
    if (!hold_connections(port, MAX_CONNECTIONS, held))
        return;
    int extra = open_connection(port);
    expect_error(extra, 0, FC_ERR_LIMIT);
    expect_closed(extra);
    close(extra);
    for (int i = 0; i < MAX_CONNECTIONS; i++) {
        if (held[i] >= 0)
            expect_renders(held[i], 100 + 10 * (uint32_t)i);
        close(held[i]);
    }
}

/* Which timeout closed a connection is told by its message, not by how long it
 * took: a loaded machine may take seconds to render. It never fires early. */
static void test_read_timeout(uint16_t port)
{
    int fds[2];
    if (!hold_connections(port, 2, fds))
        return;
    int stalled = fds[0], other = fds[1];
    static const uint8_t partial_header[5] = {'F', 'C', 'S', 'T', 3};
    fc_error err;
    double start = now_ms();
    CHECK_MSG(fc_test_send(stalled, partial_header, sizeof partial_header, &err) == FC_OK, "%s", err.message);
    expect_renders(other, 200);
    expect_error_saying(stalled, FC_ERR_LIMIT, "read timeout");
    double waited = now_ms() - start;
    CHECK_MSG(waited >= READ_TIMEOUT_MS - 5, "closed after %.0f ms, before the read timeout", waited);
    expect_closed(stalled);
    close(stalled);
    expect_renders(other, 210);   /* the other client's connection is untouched */
    close(other);
}

static void test_idle_timeout(uint16_t port)
{
    double start = now_ms();   /* before HELLO, the daemon's last message from it: never after */
    int idle = authenticated_connection(port);
    expect_error_saying(idle, FC_ERR_LIMIT, "idle timeout");
    double waited = now_ms() - start;
    CHECK_MSG(waited >= IDLE_TIMEOUT_MS - 5, "closed after %.0f ms, before the idle timeout", waited);
    expect_closed(idle);
    close(idle);
}

static bool write_token_file(test_env *env)
{
    snprintf(env->dir, sizeof env->dir, "/tmp/fc_auth_test_XXXXXX");
    if (!mkdtemp(env->dir))
        return false;
    snprintf(env->token_file, sizeof env->token_file, "%s/token", env->dir);
    FILE *f = fopen(env->token_file, "w");
    bool ok = f && fputs(TOKEN "\n", f) >= 0;
    return f && fclose(f) == 0 && ok;
}

int main(void)
{
    test_env env;
    if (!write_token_file(&env)) {
        fprintf(stderr, "cannot write the token file\n");
        return 1;
    }
    char max_connections[16], read_timeout[16], idle_timeout[16];
    snprintf(max_connections, sizeof max_connections, "%d", MAX_CONNECTIONS);
    snprintf(read_timeout, sizeof read_timeout, "%d", READ_TIMEOUT_MS);
    snprintf(idle_timeout, sizeof idle_timeout, "%d", IDLE_TIMEOUT_MS);
    const char *const args[] = {"--token-file", env.token_file, "--max-connections", max_connections,
                                "--read-timeout-ms", read_timeout, "--idle-timeout-ms", idle_timeout, NULL};
    fc_test_daemon daemon;
    fc_error err;
    unsetenv("FLUIDCAST_TOKEN");
    if (fc_test_daemon_start(&daemon, args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start the daemon: %s\n", err.message);
        return 1;
    }
    env.port = daemon.port;
    snprintf(env.server, sizeof env.server, "127.0.0.1:%u", (unsigned)daemon.port);
    test_raw_tokens(env.port);
    test_nothing_before_hello(env.port);
    test_library(&env);
    test_cli(&env);
    test_max_connections(env.port);
    test_read_timeout(env.port);
    test_idle_timeout(env.port);
    CHECK_MSG(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    char path[128];
    snprintf(path, sizeof path, "%s/ball.f32", env.dir);
    unlink(path);
    snprintf(path, sizeof path, "%s/ball.png", env.dir);
    unlink(path);
    unlink(env.token_file);
    return test_result();
}
