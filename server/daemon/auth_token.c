/* auth_token.c — loading the shared secret, comparing tokens in constant time. */
#include "auth_token.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"

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

static fc_code load_file(const char *path, fc_auth_token *out, fc_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "--token-file %s: %s", path, strerror(errno));
    /* One byte beyond the limit plus a CRLF, to tell an overlong token from one with a line end. */
    char text[FC_HELLO_TOKEN_MAX + 3];
    size_t len = fread(text, 1, sizeof text, f);
    bool failed = ferror(f) != 0;
    bool more = !failed && len == sizeof text && fgetc(f) != EOF;
    fclose(f);
    if (failed)
        return fc_error_set(err, FC_ERR_IO, "--token-file %s: read error", path);
    if (more)
        return fc_error_set(err, FC_ERR_USAGE, "--token-file %s: the token is longer than %d bytes", path,
                            FC_HELLO_TOKEN_MAX);
    if (len > 0 && text[len - 1] == '\n')
        len--;
    if (len > 0 && text[len - 1] == '\r')
        len--;
    return set_token(text, len, path, out, err);
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
