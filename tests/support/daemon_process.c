/* daemon_process.c — start, find and stop the real fluidcastd. */
#include "daemon_process.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"

#ifndef FC_FLUIDCASTD_PATH
#error "FC_FLUIDCASTD_PATH must name the fluidcastd binary (set by tests/support/CMakeLists.txt)"
#endif

enum { POLL_INTERVAL_MS = 20, MAX_EXTRA_ARGS = 16 };

const char *fc_test_daemon_path(void)
{
    return FC_FLUIDCASTD_PATH;
}

static void sleep_ms(int ms)
{
    struct timespec pause = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&pause, NULL);
}

static void remove_temp_files(fc_test_daemon *d)
{
    if (d->port_file[0])
        unlink(d->port_file);
    if (d->dir[0])
        rmdir(d->dir);
    d->port_file[0] = d->dir[0] = '\0';
}

/* "exited with status 3" / "killed by signal 11", for failure messages. */
static void describe_status(int status, char *out, size_t size)
{
    if (WIFEXITED(status))
        snprintf(out, size, "exited with status %d", WEXITSTATUS(status));
    else if (WIFSIGNALED(status))
        snprintf(out, size, "killed by signal %d", WTERMSIG(status));
    else
        snprintf(out, size, "stopped (status 0x%x)", status);
}

/* In the child: the setup's address-space limit and environment. */
static void apply_setup(const fc_test_daemon_setup *setup)
{
    if (setup->address_space_limit > 0) {
        struct rlimit limit = {setup->address_space_limit, setup->address_space_limit};
        if (setrlimit(RLIMIT_AS, &limit) != 0) {
            fprintf(stderr, "setrlimit(RLIMIT_AS): %s\n", strerror(errno));
            _exit(127);
        }
    }
    for (int i = 0; setup->environment && setup->environment[i]; i++)
        if (putenv((char *)setup->environment[i]) != 0)
            _exit(127);
}

static void spawn(const fc_test_daemon *d, const char *path, const fc_test_daemon_setup *setup, pid_t test_pid)
{
    /* A test that crashes (or is aborted by a sanitizer) takes its daemon
     * along, instead of leaving it holding ctest's output pipe open until the
     * test's timeout. */
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != test_pid)
        _exit(127);
    apply_setup(setup);
    const char *argv[8 + MAX_EXTRA_ARGS] = {path, "--listen", "127.0.0.1:0", "--port-file",
                                            d->port_file, "--gpu", "software"};
    int argc = 7;
    for (int i = 0; setup->extra_args && setup->extra_args[i] && i < MAX_EXTRA_ARGS; i++)
        argv[argc++] = setup->extra_args[i];
    argv[argc] = NULL;
    execv(argv[0], (char *const *)argv);
    fprintf(stderr, "cannot run %s: %s\n", argv[0], strerror(errno));
    _exit(127);
}

/* The port once the daemon has written it, 0 before. */
static unsigned read_port_file(const char *path)
{
    FILE *f = fopen(path, "r");
    unsigned port = 0;
    if (!f)
        return 0;
    if (fscanf(f, "%u", &port) != 1)
        port = 0;
    fclose(f);
    return port;
}

static fc_code wait_for_port(fc_test_daemon *d, const char *path, int timeout_ms, fc_error *err)
{
    for (int waited = 0; waited <= timeout_ms; waited += POLL_INTERVAL_MS) {
        unsigned port = read_port_file(d->port_file);
        if (port > 0 && port <= 65535) {
            d->port = (uint16_t)port;
            return FC_OK;
        }
        int status;
        if (waitpid(d->pid, &status, WNOHANG) == d->pid) {
            char how[64];
            describe_status(status, how, sizeof how);
            d->pid = 0;
            d->early_exit = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            return fc_error_set(err, FC_ERR_IO, "%s %s before announcing its port", path, how);
        }
        sleep_ms(POLL_INTERVAL_MS);
    }
    kill(d->pid, SIGKILL);
    waitpid(d->pid, NULL, 0);
    d->pid = 0;
    return fc_error_set(err, FC_ERR_IO, "%s did not announce its port within %d ms", path,
                        timeout_ms);
}

fc_code fc_test_daemon_start(fc_test_daemon *d, const char *const *extra_args, int timeout_ms, fc_error *err)
{
    fc_test_daemon_setup setup = {.extra_args = extra_args};
    return fc_test_daemon_start_with(d, &setup, timeout_ms, err);
}

fc_code fc_test_daemon_start_with(fc_test_daemon *d, const fc_test_daemon_setup *setup, int timeout_ms,
                                  fc_error *err)
{
    const char *path = setup->daemon_path ? setup->daemon_path : fc_test_daemon_path();
    memset(d, 0, sizeof *d);
    d->early_exit = -1;
    snprintf(d->dir, sizeof d->dir, "/tmp/fc-test-XXXXXX");
    if (!mkdtemp(d->dir)) {
        d->dir[0] = '\0';
        return fc_error_set(err, FC_ERR_IO, "mkdtemp: %s", strerror(errno));
    }
    snprintf(d->port_file, sizeof d->port_file, "%s/port", d->dir);
    pid_t test_pid = getpid();
    d->pid = fork();
    if (d->pid < 0) {
        d->pid = 0;
        remove_temp_files(d);
        return fc_error_set(err, FC_ERR_IO, "fork: %s", strerror(errno));
    }
    if (d->pid == 0)
        spawn(d, path, setup, test_pid);
    fc_code code = wait_for_port(d, path, timeout_ms, err);
    if (code != FC_OK)
        remove_temp_files(d);
    return code;
}

fc_code fc_test_daemon_stop(fc_test_daemon *d, int timeout_ms, fc_error *err)
{
    if (d->pid == 0)
        return fc_error_set(err, FC_ERR_USAGE, "the daemon is not running");
    pid_t pid = d->pid;
    d->pid = 0;
    kill(pid, SIGTERM);
    int status = 0;
    pid_t done = 0;
    for (int waited = 0; done == 0 && waited <= timeout_ms; waited += POLL_INTERVAL_MS) {
        done = waitpid(pid, &status, WNOHANG);
        if (done == 0)
            sleep_ms(POLL_INTERVAL_MS);
    }
    remove_temp_files(d);
    if (done != pid) {
        kill(pid, SIGKILL);
        waitpid(pid, NULL, 0);
        return fc_error_set(err, FC_ERR_IO, "fluidcastd ignored SIGTERM for %d ms (killed)", timeout_ms);
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        char how[64];
        describe_status(status, how, sizeof how);
        return fc_error_set(err, FC_ERR_IO, "fluidcastd %s after SIGTERM, expected exit status 0", how);
    }
    return FC_OK;
}
