/* fc_token_file.c — see fc_token_file.h. */
#include "fc_token_file.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_file.h"

/* What the token may not hold, or NULL. */
static const char *token_problem(const char *text, size_t len)
{
    if (len == 0)
        return "the file holds no token";
    if (len > FC_HELLO_TOKEN_MAX)
        return "the token is longer than " FC_STRINGIFY(FC_HELLO_TOKEN_MAX) " bytes";
    if (memchr(text, '\0', len))
        return "the token contains a NUL byte";
    if (memchr(text, '\n', len) || memchr(text, '\r', len))
        return "the file holds more than one line";
    return NULL;
}

fc_code fc_token_file_read(const char *path, char token[FC_HELLO_TOKEN_MAX + 1], fc_error *err)
{
    uint8_t *data = NULL;
    size_t len = 0;
    fc_error read_err;
    /* The token and a CRLF; one byte more is an overlong token. */
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
    const char *problem = token_problem(text, len);
    if (problem)
        code = fc_error_set(err, FC_ERR_USAGE, "--token-file %s: %s", path, problem);
    else {
        memcpy(token, text, len);
        token[len] = '\0';
    }
    free(data);
    return code;
}
