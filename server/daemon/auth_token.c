/* auth_token.c — loading the shared secret, comparing tokens in constant time. */
#include "auth_token.h"

#include <string.h>

#include "fc_error.h"
#include "fc_token_file.h"

/* FLUIDCAST_TOKEN's value: a C string, so only its length can be wrong. */
static fc_code set_env_token(const char *value, fc_auth_token *out, fc_error *err)
{
    size_t len = strlen(value);
    if (len > FC_HELLO_TOKEN_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "FLUIDCAST_TOKEN: the token is longer than %d bytes",
                            FC_HELLO_TOKEN_MAX);
    memcpy(out->text, value, len + 1);
    return FC_OK;
}

fc_code fc_auth_token_load(const char *path, const char *env_value, fc_auth_token *out, fc_error *err)
{
    out->text[0] = '\0';
    if (path)
        return fc_token_file_read(path, out->text, err);
    if (!env_value || env_value[0] == '\0')
        return FC_OK;
    return set_env_token(env_value, out, err);
}

bool fc_auth_token_matches(const char *expected, const char *given)
{
    size_t expected_len = strlen(expected);
    size_t given_len = strlen(given);
    size_t longest = expected_len > given_len ? expected_len : given_len;
    unsigned diff = 0;
    /* No early exit: every byte of the longer string is looked at, and a length
     * difference shows up as a position where only one string has a byte. */
    for (size_t i = 0; i < longest; i++) {
        unsigned char e = i < expected_len ? (unsigned char)expected[i] : 0;
        unsigned char g = i < given_len ? (unsigned char)given[i] : 0;
        diff |= (unsigned)(e ^ g) | ((unsigned)(i < expected_len) ^ (unsigned)(i < given_len));
    }
    return diff == 0;
}
