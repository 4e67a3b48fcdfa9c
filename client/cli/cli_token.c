/* cli_token.c — see cli_token.h. */
#define _POSIX_C_SOURCE 200809L
#include "cli_token.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "fc_error.h"
#include "wire.h"

static const char OPTION[] = "--token-file";
static const char VARIABLE[] = "FLUIDCAST_TOKEN";

static fc_code publish_file_token(const char *path, fc_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "%s %s: %s", OPTION, path, strerror(errno));
    /* Room for the longest token, a CRLF and one byte more to detect an overlong one. */
    char token[FC_HELLO_TOKEN_MAX + 4];
    size_t len = fread(token, 1, sizeof token - 1, f);
    bool failed = ferror(f) != 0;
    fclose(f);
    if (failed)
        return fc_error_set(err, FC_ERR_IO, "%s %s: read error", OPTION, path);
    token[len] = '\0';
    token[strcspn(token, "\r\n")] = '\0';
    if (token[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s %s: the file holds no token", OPTION, path);
    if (strlen(token) > FC_HELLO_TOKEN_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "%s %s: the token is longer than %d bytes", OPTION, path,
                            FC_HELLO_TOKEN_MAX);
    if (setenv(VARIABLE, token, 1) != 0)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot set %s: %s", VARIABLE, strerror(errno));
    return FC_OK;
}

fc_code fc_cli_token_take(int *argc, char **argv, fc_error *err)
{
    return fc_cli_take_global(argc, argv, OPTION, publish_file_token, err);
}

const char *fc_cli_token(void)
{
    const char *token = getenv(VARIABLE);
    return token && token[0] != '\0' ? token : NULL;
}
