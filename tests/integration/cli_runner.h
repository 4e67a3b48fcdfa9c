/* cli_runner.h — runs the real fluidcast binary with captured stdout/stderr. */
#ifndef FC_CLI_RUNNER_H
#define FC_CLI_RUNNER_H

#include <stddef.h>
#include <stdint.h>

#define CLI_CAPTURE_MAX 4096

typedef struct cli_result {
    int status;                    /* exit status; -1 when it did not exit normally */
    char out[CLI_CAPTURE_MAX];     /* stdout, NUL-terminated (truncated if longer) */
    char err[CLI_CAPTURE_MAX];     /* stderr, likewise */
} cli_result;

/* Runs `cli_path` with args (NULL-terminated, without argv[0]); the output is
 * captured through files in scratch_dir. */
void cli_run(const char *cli_path, const char *scratch_dir, const char *const *args, cli_result *r);

/* The whole file in a malloc'd buffer (*size bytes), or NULL. */
uint8_t *read_whole_file(const char *path, size_t *size);

#endif
