/* client_render.c — RENDER and waiting for its IMAGE (or ERROR), with the
 * rejections of earlier requests that arrive on the way. */
#include "fluidcast.h"

#include <stdlib.h>
#include <string.h>

#include "client_await.h"
#include "client_core.h"
#include "fc_error.h"

static fc_code send_render(fc_client *c, const fc_render_request *request, uint32_t *id, fc_error *err)
{
    *id = fc_client_next_request_id(c);
    fc_buf_reset(&c->tx);
    fc_code code = fc_wire_write_render(&c->tx, *id, request, err);
    return code != FC_OK ? code : fc_client_send_tx(c, err);
}

/* Copies the IMAGE payload in c->rx into *out, which then owns its bytes. */
static fc_code take_image(fc_client *c, fc_image_result *out, fc_error *err)
{
    fc_image_reply reply;
    fc_error why;
    if (fc_wire_read_image(c->rx.data, c->rx.len, &reply, &why) != FC_OK) {
        c->broken = true;
        return fc_error_set(err, FC_ERR_PROTOCOL, "malformed IMAGE from the server: %s", why.message);
    }
    uint8_t *data = malloc(reply.size ? (size_t)reply.size : 1);
    if (!data)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %llu-byte image",
                            (unsigned long long)reply.size);
    memcpy(data, reply.data, (size_t)reply.size);
    out->width = reply.width;
    out->height = reply.height;
    out->format = reply.format;
    out->aov = reply.aov;
    memcpy(out->stage_ms, reply.stage_ms, sizeof out->stage_ms);
    out->data = data;
    out->size = (size_t)reply.size;
    return FC_OK;
}

fc_code fc_client_render(fc_client *client, const fc_render_request *request,
                         fc_image_result *out, fc_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!request || !out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_client_render needs a request and a result");
    uint32_t id;
    code = send_render(client, request, &id, err);
    if (code != FC_OK)
        return code;

    fc_error cause;
    fc_error_clear(&cause);
    fc_error reply;
    /* The first ERROR answering an earlier request explains what the render
     * used (or why it failed) better than the render's own reply. */
    code = fc_client_await_reply(client, id, FC_MSG_IMAGE, &cause, &reply);
    if (code == FC_OK)
        code = take_image(client, out, &reply);
    /* An earlier rejection is the cause, also when the connection then failed:
     * a server that closes after an ERROR has said why. */
    if (cause.code != FC_OK) {
        fc_image_result_free(out);
        reply = cause;
        code = cause.code;
    }
    if (code != FC_OK && err)
        *err = reply;
    return code;
}

void fc_image_result_free(fc_image_result *result)
{
    if (!result)
        return;
    free(result->data);
    memset(result, 0, sizeof *result);
}
