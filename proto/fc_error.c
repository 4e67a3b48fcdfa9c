/* fc_error.c — building and naming error values. */
#include "fc_error.h"

#include <stdarg.h>
#include <stdio.h>

fc_code fc_error_set(fc_error *err, fc_code code, const char *fmt, ...)
{
    if (err) {
        err->code = code;
        va_list args;
        va_start(args, fmt);
        /* vsnprintf truncates and always NUL-terminates; a long reason is cut, never overflows. */
        int written = vsnprintf(err->message, sizeof err->message, fmt, args);
        va_end(args);
        if (written < 0)
            err->message[0] = '\0';
    }
    return code;
}

void fc_error_clear(fc_error *err)
{
    if (err) {
        err->code = FC_OK;
        err->message[0] = '\0';
    }
}

const char *fc_code_name(fc_code code)
{
    switch (code) {
    case FC_OK: return "ok";
    case FC_ERR_BAD_MAGIC: return "bad_magic";
    case FC_ERR_VERSION: return "version";
    case FC_ERR_UNKNOWN_TYPE: return "unknown_type";
    case FC_ERR_TOO_LARGE: return "too_large";
    case FC_ERR_MALFORMED: return "malformed";
    case FC_ERR_BAD_STATE: return "bad_state";
    case FC_ERR_INVALID_VALUE: return "invalid_value";
    case FC_ERR_LIMIT: return "limit";
    case FC_ERR_RENDER: return "render";
    case FC_ERR_ENCODE: return "encode";
    case FC_ERR_INTERNAL: return "internal";
    case FC_ERR_UNAUTHORIZED: return "unauthorized";
    case FC_ERR_DUPLICATE: return "duplicate";
    case FC_ERR_INCONSISTENT: return "inconsistent";
    case FC_ERR_INCOMPLETE: return "incomplete";
    case FC_ERR_TLS_REQUIRED: return "tls_required";
    case FC_ERR_IO: return "io";
    case FC_ERR_CONNECT: return "connect";
    case FC_ERR_CLOSED: return "closed";
    case FC_ERR_PROTOCOL: return "protocol";
    case FC_ERR_PARSE: return "parse";
    case FC_ERR_GL: return "gl";
    case FC_ERR_NOMEM: return "nomem";
    case FC_ERR_USAGE: return "usage";
    case FC_ERR_TLS_UNKNOWN_CA: return "tls_unknown_ca";
    case FC_ERR_TLS_NAME_MISMATCH: return "tls_name_mismatch";
    case FC_ERR_TLS_EXPIRED: return "tls_expired";
    case FC_ERR_TLS_PLAINTEXT_PEER: return "tls_plaintext_peer";
    case FC_ERR_TLS_CLIENT_CERT: return "tls_client_cert";
    case FC_ERR_TLS: return "tls";
    }
    return "unknown";
}
