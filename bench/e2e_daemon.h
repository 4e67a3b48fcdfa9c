/* e2e_daemon.h — the fluidcastd the end-to-end benchmark starts for itself:
 * on an ephemeral port of 127.0.0.1, stopped with SIGTERM. */
#ifndef FC_E2E_DAEMON_H
#define FC_E2E_DAEMON_H

#include <sys/types.h>

#include "fluidcast_types.h"

typedef struct e2e_daemon {
    pid_t pid;                 /* 0 when not running */
    char dir[64];              /* temporary directory holding the port file */
    char port_file[96];
    char address[32];          /* "127.0.0.1:PORT" once started */
} e2e_daemon;

/* The fluidcastd in the directory of the running executable, into `out`. */
fc_code e2e_daemon_default_path(char *out, size_t size, fc_error *err);

/* Runs `path` --listen 127.0.0.1:0 --port-file TMP --gpu `gpu` --log-level warn and waits (up
 * to 60 s: llvmpipe compiles every shader first) for its port. */
fc_code e2e_daemon_start(e2e_daemon *d, const char *path, const char *gpu, fc_error *err);

/* SIGTERM, then waits; FC_ERR_IO unless it exited with status 0. */
fc_code e2e_daemon_stop(e2e_daemon *d, fc_error *err);

#endif
