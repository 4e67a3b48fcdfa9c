/* test_socket_parts.c — fc_socket_send_parts, the scatter send FRAMEs leave
 * libfluidcast by. A blocking sendmsg returns early only when a signal
 * interrupts it: a 1 ms interval timer does so again and again while a slow
 * reader keeps a small socket buffer full, so sends stop part-way (inside a
 * part, at a part's end, around an empty part) and the reader must still get
 * exactly the concatenation. A vanished peer is FC_ERR_CLOSED, not a SIGPIPE. */
#include <pthread.h>
#include <signal.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "socket_io.h"
#include "test_util.h"

enum { PARTS = 5, READ_STEP = 777 };
static const size_t part_sizes[PARTS] = {1, 16, 300001, 0, 123457};

typedef struct reader {
    int fd;
    uint8_t *data;
    size_t len, cap;
} reader;

static void on_alarm(int signal_number)
{
    (void)signal_number;
}

/* Reads in small, slow steps until the writer closes; the timer's signals go to the writer. */
static void *read_all(void *arg)
{
    reader *r = arg;
    sigset_t alarm;
    sigemptyset(&alarm);
    sigaddset(&alarm, SIGALRM);
    pthread_sigmask(SIG_BLOCK, &alarm, NULL);
    const struct timespec pause = {.tv_nsec = 50 * 1000};
    uint8_t surplus[READ_STEP];
    for (;;) {
        nanosleep(&pause, NULL);
        /* Bytes beyond the expected ones are counted, not kept, so the writer never blocks on them. */
        bool room = r->len + READ_STEP <= r->cap;
        ssize_t n = read(r->fd, room ? r->data + r->len : surplus, READ_STEP);
        if (n <= 0)
            break;
        r->len += (size_t)n;
    }
    return NULL;
}

static void test_partial_sends(void)
{
    int fds[2];
    CHECK(socketpair(AF_UNIX, SOCK_STREAM, 0, fds) == 0);
    int small = 4096;
    CHECK(setsockopt(fds[0], SOL_SOCKET, SO_SNDBUF, &small, sizeof small) == 0);

    size_t total = 0;
    for (int i = 0; i < PARTS; i++)
        total += part_sizes[i];
    uint8_t *expected = malloc(total);
    CHECK(expected != NULL);
    if (!expected)
        return;
    for (size_t i = 0; i < total; i++)
        expected[i] = (uint8_t)(i * 131 + i / 251);
    struct iovec parts[PARTS];
    size_t offset = 0;
    for (int i = 0; i < PARTS; i++) {
        parts[i] = (struct iovec){.iov_base = expected + offset, .iov_len = part_sizes[i]};
        offset += part_sizes[i];
    }

    reader r = {.fd = fds[1], .cap = total + READ_STEP};
    r.data = malloc(r.cap);
    pthread_t thread;
    /* Without its reader the test cannot go on: nothing to join, nobody to drain the socket. */
    bool reading = r.data != NULL && pthread_create(&thread, NULL, read_all, &r) == 0;
    CHECK(reading);
    if (!reading) {
        close(fds[0]);
        close(fds[1]);
        free(r.data);
        free(expected);
        return;
    }
    /* No SA_RESTART: an interrupted sendmsg returns what it sent so far. */
    struct sigaction action = {.sa_handler = on_alarm};
    sigemptyset(&action.sa_mask);
    CHECK(sigaction(SIGALRM, &action, NULL) == 0);
    struct itimerval every_ms = {.it_interval = {.tv_usec = 1000}, .it_value = {.tv_usec = 1000}};
    CHECK(setitimer(ITIMER_REAL, &every_ms, NULL) == 0);
    fc_error err;
    CHECK_CODE(fc_socket_send_parts(fds[0], parts, PARTS, &err), FC_OK);
    struct itimerval off = {0};
    setitimer(ITIMER_REAL, &off, NULL);
    close(fds[0]);
    pthread_join(thread, NULL);
    CHECK_MSG(r.len == total, "received %zu of %zu bytes", r.len, total);
    CHECK(r.len == total && memcmp(r.data, expected, total) == 0);
    close(fds[1]);
    free(r.data);
    free(expected);
}

static void test_peer_gone(void)
{
    int fds[2];
    CHECK(socketpair(AF_UNIX, SOCK_STREAM, 0, fds) == 0);
    close(fds[1]);
    uint8_t bytes[64] = {0};
    struct iovec parts[2] = {{.iov_base = bytes, .iov_len = 10}, {.iov_base = bytes + 10, .iov_len = 54}};
    fc_error err;
    CHECK_CODE(fc_socket_send_parts(fds[0], parts, 2, &err), FC_ERR_CLOSED);
    close(fds[0]);
}

int main(void)
{
    /* The default action would end the test: MSG_NOSIGNAL must make it an error value. */
    signal(SIGPIPE, SIG_DFL);
    test_partial_sends();
    test_peer_gone();
    return test_result();
}
