/* conversation_reply.c — queueing on a client's output: ERROR replies (local codes
 * become wire codes) and whole messages, within the client's memory limit. */
#include "conversations/conversation_internal.h"

#include <string.h>

#include "conversations/conversation_memory.h"
#include "fc_error.h"

/* Codes >= 100 never travel: each becomes the wire code a client can act on. */
static fc_code wire_code(fc_code code)
{
    if (code >= 1 && code <= 99)
        return code;
    return code == FC_ERR_GL ? FC_ERR_RENDER : FC_ERR_INTERNAL;
}

fc_conversation_verdict fc_conversation_reply_error(const fc_daemon_context *ctx, const char *peer, uint32_t request_id,
                                                    const fc_error *error, fc_conversation_verdict then, fc_buf *out)
{
    fc_error wire = *error;
    wire.code = wire_code(error->code);
    /* Client mistakes are routine; failures on the server's side deserve attention. */
    int server_side = wire.code == FC_ERR_RENDER || wire.code == FC_ERR_ENCODE || wire.code == FC_ERR_INTERNAL;
    fc_log_write(ctx->log, server_side ? FC_LOG_WARN : FC_LOG_INFO, "%s: request %u: %s: %s%s", peer,
                 (unsigned)request_id, fc_code_name(wire.code), wire.message,
                 then == FC_CONV_CLOSE ? " (closing)" : "");
    if (wire.code == FC_ERR_LIMIT)
        fc_metrics_add(ctx->metrics, FC_METRIC_LIMIT_REJECTIONS, 1);
    fc_error write_err;
    if (fc_wire_write_error(out, request_id, &wire, &write_err) != FC_OK) {
        fc_log_write(ctx->log, FC_LOG_ERROR, "%s: cannot queue ERROR: %s", peer, write_err.message);
        return FC_CONV_ABORT;
    }
    return then;
}

void fc_conversation_send_error(fc_conversation *c, uint32_t request_id, const fc_error *err)
{
    fc_conversation_reply_error(c->ctx, c->peer, request_id, err, FC_CONV_CONTINUE, c->out);
}

fc_code fc_conversation_queue_message(fc_conversation *c, const fc_buf *message, const char *what, fc_error *err)
{
    fc_code code = fc_conversation_memory_admit(c, 0, message->len, what, err);
    if (code != FC_OK)
        return code;
    if (!fc_buf_reserve(c->out, message->len)) {
        c->out->failed = false;
        return fc_error_set(err, FC_ERR_INTERNAL, "no memory to queue %s of %zu bytes", what, message->len);
    }
    memcpy(c->out->data + c->out->len, message->data, message->len);
    c->out->len += message->len;
    return FC_OK;
}
