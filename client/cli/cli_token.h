/* cli_token.h — the daemon's shared secret for every subcommand: from
 * `--token-file PATH` anywhere on the command line, else FLUIDCAST_TOKEN. */
#ifndef FC_CLI_TOKEN_H
#define FC_CLI_TOKEN_H

#include "fluidcast_types.h"

/* Removes "--token-file PATH" / "--token-file=PATH" from argv (updating
 * *argc) and publishes the file's first line as FLUIDCAST_TOKEN, so that the
 * subcommands have one place to look. FC_ERR_USAGE for a missing value or an
 * empty token, FC_ERR_IO for an unreadable file. */
fc_code fc_cli_token_take(int *argc, char **argv, fc_error *err);

/* The token to send in HELLO, or NULL for none. */
const char *fc_cli_token(void);

#endif
