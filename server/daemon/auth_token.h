/* auth_token.h — the daemon's shared secret: where it comes from (a file or
 * FLUIDCAST_TOKEN) and the constant-time check of the token a HELLO carries. */
#ifndef FC_DAEMON_AUTH_TOKEN_H
#define FC_DAEMON_AUTH_TOKEN_H

#include <stdbool.h>

#include "fluidcast_types.h"
#include "wire.h"

typedef struct fc_auth_token {
    char text[FC_HELLO_TOKEN_MAX + 1];   /* "" = no authentication */
} fc_auth_token;

/* Reads the token from path (fc_token_file_read, as the clients do), or from
 * env_value when path is NULL; env_value NULL or empty (with no path) means no
 * token. FC_ERR_USAGE for an empty, overlong or NUL-containing token or a
 * file of more than one line, FC_ERR_IO for an unreadable file. */
fc_code fc_auth_token_load(const char *path, const char *env_value, fc_auth_token *out, fc_error *err);

static inline bool fc_auth_token_required(const fc_auth_token *t)
{
    return t->text[0] != '\0';
}

/* True when given equals expected. Takes the same time whatever the bytes,
 * so a client cannot find the secret byte by byte from response times. */
bool fc_auth_token_matches(const char *expected, const char *given);

#endif
