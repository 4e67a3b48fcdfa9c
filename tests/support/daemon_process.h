/* daemon_process.h — runs the real fluidcastd for integration tests and the
 * end-to-end benchmark: on an ephemeral port of 127.0.0.1 with software GL,
 * stopped with SIGTERM. */
#ifndef FC_TEST_DAEMON_PROCESS_H
#define FC_TEST_DAEMON_PROCESS_H

#include <stdint.h>
#include <sys/types.h>

#include "fluidcast_types.h"

/* Enough for llvmpipe to create a context and compile every shader on a busy machine. */
#define FC_TEST_DAEMON_START_TIMEOUT_MS 60000
#define FC_TEST_DAEMON_STOP_TIMEOUT_MS 10000

typedef struct fc_test_daemon {
    pid_t pid;             /* 0 when not running */
    int early_exit;        /* exit status when it ended before announcing a port, else -1 */
    uint16_t port;
    char dir[64];          /* temporary directory holding the port file */
    char port_file[128];
} fc_test_daemon;

/* The fluidcastd binary the tests were built with. */
const char *fc_test_daemon_path(void);

/* Starts fluidcastd --listen 127.0.0.1:0 --port-file <tmp> --gpu software plus
 * extra_args (NULL-terminated list, or NULL) and waits for it to announce its
 * port. FC_ERR_IO when it exits first (early_exit says how) or does not
 * announce within timeout_ms (it is killed then). Later arguments override
 * earlier ones, so extra_args may replace the defaults. */
fc_code fc_test_daemon_start(fc_test_daemon *d, const char *const *extra_args, int timeout_ms, fc_error *err);

/* What a test may change about the daemon's process beyond its arguments. */
typedef struct fc_test_daemon_setup {
    const char *daemon_path;            /* the binary to run; NULL: fc_test_daemon_path() */
    const char *const *extra_args;      /* as for fc_test_daemon_start */
    uint64_t address_space_limit;       /* RLIMIT_AS set in the child before exec, bytes; 0 = inherited */
    const char *const *environment;     /* "NAME=VALUE" entries added to its environment, NULL-terminated; or NULL */
} fc_test_daemon_setup;

/* fc_test_daemon_start with the setup's binary, limit and environment. */
fc_code fc_test_daemon_start_with(fc_test_daemon *d, const fc_test_daemon_setup *setup, int timeout_ms,
                                  fc_error *err);

/* Sends SIGTERM and waits up to timeout_ms. FC_OK only when the daemon exited
 * with status 0; FC_ERR_IO otherwise (killed with SIGKILL if still running). */
fc_code fc_test_daemon_stop(fc_test_daemon *d, int timeout_ms, fc_error *err);

#endif
