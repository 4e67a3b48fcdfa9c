/* fc_token_file.h — the shared secret's file (--token-file of fluidcastd and of
 * every fluidcast subcommand), read the same way on both sides. */
#ifndef FC_TOKEN_FILE_H
#define FC_TOKEN_FILE_H

#include "fluidcast_types.h"
#include "wire.h"   /* FC_HELLO_TOKEN_MAX */

/* The file holds the token on one line, optionally ended by LF or CRLF.
 * Errors begin "--token-file PATH: ": FC_ERR_IO when the file cannot be read,
 * FC_ERR_USAGE for no token, one longer than FC_HELLO_TOKEN_MAX bytes, or one
 * holding a NUL byte or a line end (a second line). */
fc_code fc_token_file_read(const char *path, char token[FC_HELLO_TOKEN_MAX + 1], fc_error *err);

#endif
