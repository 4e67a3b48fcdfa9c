/* cli_runner.c — see cli_runner.h. */
#include "cli_runner.h"

#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

static void read_capture(const char *path, char *out)
{
    size_t size = 0;
    uint8_t *data = read_whole_file(path, &size);
    if (size >= CLI_CAPTURE_MAX)
        size = CLI_CAPTURE_MAX - 1;
    if (data)
        memcpy(out, data, size);
    out[data ? size : 0] = '\0';
    free(data);
    unlink(path);
}

void cli_run(const char *cli_path, const char *scratch_dir, const char *const *args, cli_result *r)
{
    char out_path[512], err_path[512];
    snprintf(out_path, sizeof out_path, "%s/cli.stdout", scratch_dir);
    snprintf(err_path, sizeof err_path, "%s/cli.stderr", scratch_dir);
    const char *argv[32] = { cli_path };
    int argc = 1;
    while (args[argc - 1] && argc < 31) {
        argv[argc] = args[argc - 1];
        argc++;
    }
    argv[argc] = NULL;

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    pid_t pid;
    int status = 0;
    r->status = -1;
    if (posix_spawn(&pid, cli_path, &actions, NULL, (char *const *)argv, environ) == 0 &&
        waitpid(pid, &status, 0) == pid && WIFEXITED(status))
        r->status = WEXITSTATUS(status);
    posix_spawn_file_actions_destroy(&actions);
    read_capture(out_path, r->out);
    read_capture(err_path, r->err);
}

uint8_t *read_whole_file(const char *path, size_t *size)
{
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, len = 0;
    uint8_t *data = malloc(cap);
    size_t got;
    while (data && (got = fread(data + len, 1, cap - len, f)) > 0) {
        len += got;
        if (len == cap) {
            uint8_t *grown = realloc(data, cap *= 2);
            if (!grown)
                free(data);
            data = grown;
        }
    }
    fclose(f);
    *size = data ? len : 0;
    return data;
}
