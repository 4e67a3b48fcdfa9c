/* e2e_daemon.c — start and stop the benchmark's own fluidcastd. */
#include "e2e_daemon.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"

enum { POLL_MS = 20, START_TIMEOUT_MS = 60000, STOP_TIMEOUT_MS = 10000 };

static void sleep_ms(int ms)
{
    struct timespec pause = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&pause, NULL);
}

fc_code e2e_daemon_default_path(char *out, size_t size, fc_error *err)
{
    char self[4096];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0)
        return fc_error_set(err, FC_ERR_IO, "cannot find this executable (/proc/self/exe): %s", strerror(errno));
    self[n] = '\0';
    char *slash = strrchr(self, '/');
    *slash = '\0';
    if ((size_t)snprintf(out, size, "%s/fluidcastd", self) >= size)
        return fc_error_set(err, FC_ERR_IO, "path of fluidcastd too long");
    return FC_OK;
}

static void remove_temp_files(e2e_daemon *d)
{
    if (d->port_file[0])
        unlink(d->port_file);
    if (d->dir[0])
        rmdir(d->dir);
    d->port_file[0] = d->dir[0] = '\0';
}

static void exec_daemon(const e2e_daemon *d, const char *path, const char *gpu, pid_t parent)
{
    /* A benchmark killed by ^C takes its daemon along. */
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent)
        _exit(127);
    /* Warnings only: its per-connection info lines would bury the benchmark's progress. */
    const char *argv[] = {path, "--listen", "127.0.0.1:0", "--port-file", d->port_file, "--gpu", gpu,
                          "--log-level", "warn", NULL};
    execv(path, (char *const *)argv);
    fprintf(stderr, "cannot run %s: %s\n", path, strerror(errno));
    _exit(127);
}

static unsigned read_port(const char *path)
{
    FILE *f = fopen(path, "r");
    unsigned port = 0;
    if (!f)
        return 0;
    if (fscanf(f, "%u", &port) != 1 || port > 65535)
        port = 0;
    fclose(f);
    return port;
}

static fc_code wait_for_port(e2e_daemon *d, const char *path, fc_error *err)
{
    for (int waited = 0; waited <= START_TIMEOUT_MS; waited += POLL_MS) {
        unsigned port = read_port(d->port_file);
        if (port) {
            snprintf(d->address, sizeof d->address, "127.0.0.1:%u", port);
            return FC_OK;
        }
        int status;
        if (waitpid(d->pid, &status, WNOHANG) == d->pid) {
            d->pid = 0;
            return fc_error_set(err, FC_ERR_IO, "%s exited (status 0x%x) before announcing its port", path, status);
        }
        sleep_ms(POLL_MS);
    }
    kill(d->pid, SIGKILL);
    waitpid(d->pid, NULL, 0);
    d->pid = 0;
    return fc_error_set(err, FC_ERR_IO, "%s did not announce its port within %d ms", path, START_TIMEOUT_MS);
}

fc_code e2e_daemon_start(e2e_daemon *d, const char *path, const char *gpu, fc_error *err)
{
    memset(d, 0, sizeof *d);
    snprintf(d->dir, sizeof d->dir, "/tmp/fc-e2e-XXXXXX");
    if (!mkdtemp(d->dir)) {
        d->dir[0] = '\0';
        return fc_error_set(err, FC_ERR_IO, "mkdtemp: %s", strerror(errno));
    }
    snprintf(d->port_file, sizeof d->port_file, "%s/port", d->dir);
    pid_t parent = getpid();
    d->pid = fork();
    if (d->pid < 0) {
        d->pid = 0;
        remove_temp_files(d);
        return fc_error_set(err, FC_ERR_IO, "fork: %s", strerror(errno));
    }
    if (d->pid == 0)
        exec_daemon(d, path, gpu, parent);
    fc_code code = wait_for_port(d, path, err);
    if (code != FC_OK)
        remove_temp_files(d);
    return code;
}

fc_code e2e_daemon_stop(e2e_daemon *d, fc_error *err)
{
    if (d->pid == 0)
        return FC_OK;
    pid_t pid = d->pid;
    d->pid = 0;
    kill(pid, SIGTERM);
    int status = 0;
    pid_t done = 0;
    for (int waited = 0; done == 0 && waited <= STOP_TIMEOUT_MS; waited += POLL_MS) {
        done = waitpid(pid, &status, WNOHANG);
        if (done == 0)
            sleep_ms(POLL_MS);
    }
    remove_temp_files(d);
    if (done != pid) {
        kill(pid, SIGKILL);
        waitpid(pid, NULL, 0);
        return fc_error_set(err, FC_ERR_IO, "fluidcastd ignored SIGTERM for %d ms (killed)", STOP_TIMEOUT_MS);
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return fc_error_set(err, FC_ERR_IO, "fluidcastd ended with status 0x%x after SIGTERM", status);
    return FC_OK;
}
