/* test_daemon_startup.c — fluidcastd's exit status when it cannot start:
 * 1 without a GL context or a listening socket, 2 for a bad command line (or
 * a malformed test hook in the environment). */
#include <string.h>

#include "daemon_process.h"
#include "fc_error.h"
#include "test_util.h"

/* Starts the daemon as `setup` says and expects it to exit with `status`
 * before listening; `what` names the case. */
static void expect_exit_with(const char *what, const fc_test_daemon_setup *setup, int status)
{
    fc_test_daemon d;
    fc_error err;
    fc_code code = fc_test_daemon_start_with(&d, setup, FC_TEST_DAEMON_START_TIMEOUT_MS, &err);
    CHECK_MSG(code == FC_ERR_IO, "%s: started (port %u) but should not have", what, (unsigned)d.port);
    CHECK_MSG(d.early_exit == status, "%s: exit status %d, expected %d", what, d.early_exit, status);
    if (code == FC_OK)
        fc_test_daemon_stop(&d, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err);
}

/* Starts the daemon with extra_args and expects it to exit with `status` before listening. */
static void expect_exit(const char *const *extra_args, int status)
{
    fc_test_daemon_setup setup = {.extra_args = extra_args};
    expect_exit_with(extra_args[0], &setup, status);
}

int main(void)
{
    /* No such EGL device: no GL context. */
    static const char *const no_gpu[] = {"--gpu", "999", NULL};
    expect_exit(no_gpu, 1);

    static const char *const bogus[] = {"--frobnicate", "1", NULL};
    expect_exit(bogus, 2);
    static const char *const bad_limit[] = {"--max-image", "0x100", NULL};
    expect_exit(bad_limit, 2);
    static const char *const no_memory[] = {"--max-session-memory", "0", NULL};
    expect_exit(no_memory, 2);
    static const char *const png_level[] = {"--png-compression", "10", NULL};
    expect_exit(png_level, 2);
    /* The lost-context test hook takes a render number or nothing. */
    static const char *const bad_hook[] = {"FLUIDCASTD_TEST_LOSE_CONTEXT=soon", NULL};
    expect_exit_with("FLUIDCASTD_TEST_LOSE_CONTEXT=soon", &(fc_test_daemon_setup){.environment = bad_hook}, 2);

    /* A port already taken by a running daemon. */
    fc_test_daemon first;
    fc_error err;
    if (fc_test_daemon_start(&first, NULL, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        CHECK_MSG(0, "cannot start the daemon: %s", err.message);
        return test_result();
    }
    char taken[32];
    snprintf(taken, sizeof taken, "127.0.0.1:%u", (unsigned)first.port);
    const char *const busy[] = {"--listen", taken, NULL};
    expect_exit(busy, 1);
    CHECK_MSG(fc_test_daemon_stop(&first, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    return test_result();
}
