/* auth_token.c — loading the shared secret, comparing tokens in constant time. */
#include "auth_token.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_file.h"

static fc_code set_token(const char *text, size_t len, const char *source, fc_auth_token *out, fc_error *err)
{
    if (len == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s: the token is empty", source);
    if (len > FC_HELLO_TOKEN_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "%s: the token is longer than %d bytes", source, FC_HELLO_TOKEN_MAX);
    if (memchr(text, '\0', len))
        return fc_error_set(err, FC_ERR_USAGE, "%s: the token contains a NUL byte", source);
    memcpy(out->text, text, len);
    out->text[len] = '\0';
    return FC_OK;
}

/* The file holds the token, optionally followed by one line end (LF or CRLF). */
static fc_code load_file(const char *path, fc_auth_token *out, fc_error *err)
{
    uint8_t *data = NULL;
    size_t len = 0;
    fc_error read_err;
    fc_code code = fc_read_file(path, FC_HELLO_TOKEN_MAX + 2, &data, &len, &read_err);
    if (code == FC_ERR_TOO_LARGE)
        return fc_error_set(err, FC_ERR_USAGE, "--token-file %s: the token is longer than %d bytes", path,
                            FC_HELLO_TOKEN_MAX);
    if (code != FC_OK)
        return fc_error_set(err, code, "--token-file %s", read_err.message);
    const char *text = (const char *)data;
    if (len > 0 && text[len - 1] == '\n')
        len--;
    if (len > 0 && text[len - 1] == '\r')
        len--;
    code = set_token(text, len, path, out, err);
    free(data);
    return code;
}

fc_code fc_auth_token_load(const char *path, const char *env_value, fc_auth_token *out, fc_error *err)
{
    out->text[0] = '\0';
    if (path)
        return load_file(path, out, err);
    if (!env_value || env_value[0] == '\0')
        return FC_OK;
    return set_token(env_value, strlen(env_value), "FLUIDCAST_TOKEN", out, err);
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
