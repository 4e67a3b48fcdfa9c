/* cli_token.c — see cli_token.h. */
#define _POSIX_C_SOURCE 200809L
#include "cli_token.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "fc_error.h"
#include "fc_token_file.h"

static const char OPTION[] = "--token-file";
static const char VARIABLE[] = "FLUIDCAST_TOKEN";

static fc_code publish_file_token(const char *path, fc_error *err)
{
    char token[FC_HELLO_TOKEN_MAX + 1];
    fc_code code = fc_token_file_read(path, token, err);
    if (code != FC_OK)
        return code;
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
