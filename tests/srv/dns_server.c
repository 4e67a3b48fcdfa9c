/* dns_server.c — see dns_server.h. Readiness is checked with libresolv
 * directly (not through libfluidcast), so a failure here is the server's. */
#include "dns_server.h"

#include <arpa/inet.h>
#include <arpa/nameser.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <resolv.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static const char *const candidates[] = {"/usr/sbin/dnsmasq", "/usr/bin/dnsmasq", NULL};

const char *fc_test_dns_binary(void)
{
    for (int i = 0; candidates[i]; i++)
        if (access(candidates[i], X_OK) == 0)
            return candidates[i];
    return NULL;
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static bool write_config(const fc_test_dns *dns, const char *path, const char *const *records)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    /* Only our records: no upstream servers, no /etc/hosts, no DHCP, loopback only. */
    fprintf(f, "port=%u\nlisten-address=127.0.0.1\nbind-interfaces\nno-resolv\nno-hosts\nno-poll\n"
               "log-queries\n",
            (unsigned)dns->port);
    for (int i = 0; records[i]; i++)
        fprintf(f, "%s\n", records[i]);
    return fclose(f) == 0;
}

static pid_t spawn(const char *config, const char *log)
{
    pid_t pid = fork();
    if (pid != 0)
        return pid;
    int fd = open(log, O_WRONLY | O_CREAT | O_APPEND, 0600);
    if (fd >= 0) {
        dup2(fd, 1);
        dup2(fd, 2);
    }
    char conf_arg[192];
    snprintf(conf_arg, sizeof conf_arg, "--conf-file=%s", config);
    /* --keep-in-foreground: it stays our child, so its pid is the one we stop;
     * --user=root: a test's temporary files need no other owner; no pid file. */
    execl(fc_test_dns_binary(), "dnsmasq", "--keep-in-foreground", "--log-facility=-", "--pid-file",
          "--user=root", conf_arg, (char *)NULL);
    _exit(127);
}

static bool answers(const fc_test_dns *dns, const char *name)
{
    struct __res_state state;
    memset(&state, 0, sizeof state);
    if (res_ninit(&state) != 0)
        return false;
    state.nsaddr_list[0].sin_family = AF_INET;
    state.nsaddr_list[0].sin_port = htons(dns->port);
    inet_pton(AF_INET, "127.0.0.1", &state.nsaddr_list[0].sin_addr);
    state.nscount = 1;
    state.retrans = 1;
    state.retry = 1;
    unsigned char answer[4096];
    int length = res_nquery(&state, name, ns_c_in, ns_t_srv, answer, sizeof answer);
    res_nclose(&state);
    return length > 0;
}

/* A port the kernel finds free on 127.0.0.1 now, rather than a random guess (0
 * when it cannot tell); dnsmasq binds it next, and if something took it
 * meanwhile, fc_test_dns_start tries another. */
static uint16_t free_port(void)
{
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t length = sizeof addr;
    uint16_t port = 0;
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (fd >= 0 && bind(fd, (const struct sockaddr *)&addr, sizeof addr) == 0 &&
        getsockname(fd, (struct sockaddr *)&addr, &length) == 0)
        port = ntohs(addr.sin_port);
    if (fd >= 0)
        close(fd);
    return port;
}

/* true once it answers; false when it exited (port taken) or stayed silent. */
static bool start_on(fc_test_dns *dns, const char *const *records, const char *ready_name)
{
    char config[128], log[128];
    snprintf(config, sizeof config, "%s/dnsmasq.conf", dns->dir);
    snprintf(log, sizeof log, "%s/dnsmasq.log", dns->dir);
    if (!write_config(dns, config, records))
        return false;
    dns->pid = spawn(config, log);
    if (dns->pid < 0)
        return false;
    for (int tries = 0; tries < 100; tries++) {
        int status;
        if (waitpid(dns->pid, &status, WNOHANG) == dns->pid) {
            fprintf(stderr, "dnsmasq on port %u exited (status %d); see %s\n", (unsigned)dns->port, status, log);
            dns->pid = 0;
            return false;
        }
        if (answers(dns, ready_name))
            return true;
        sleep_ms(100);
    }
    fprintf(stderr, "dnsmasq on port %u never answered %s; see %s\n", (unsigned)dns->port, ready_name, log);
    fc_test_dns_stop(dns);
    return false;
}

bool fc_test_dns_start(fc_test_dns *dns, const char *const *records, const char *ready_name)
{
    memset(dns, 0, sizeof *dns);
    snprintf(dns->dir, sizeof dns->dir, "/tmp/fc-dns-XXXXXX");
    if (!mkdtemp(dns->dir)) {
        perror("mkdtemp");
        return false;
    }
    for (int attempt = 0; attempt < 5; attempt++) {
        dns->port = free_port();
        if (dns->port != 0 && start_on(dns, records, ready_name))
            return true;
    }
    return false;
}

void fc_test_dns_address(const fc_test_dns *dns, char *out, size_t size)
{
    snprintf(out, size, "127.0.0.1:%u", (unsigned)dns->port);
}

bool fc_test_dns_stop(fc_test_dns *dns)
{
    if (dns->pid <= 0)
        return true;
    kill(dns->pid, SIGTERM);
    int status = 0;
    pid_t got;
    do
        got = waitpid(dns->pid, &status, 0);
    while (got < 0 && errno == EINTR);
    dns->pid = 0;
    return got > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}
