/* client_surface.c — SURFACE and waiting for all its SURFACE_PARTs (or an
 * ERROR), with the rejections of earlier requests that arrive on the way. */
#include "fluidcast.h"

#include <string.h>

#include "client_await.h"
#include "client_core.h"
#include "fc_error.h"
#include "wire_surface.h"

static fc_code send_surface(fc_client *c, uint32_t attributes, uint32_t *id, fc_error *err)
{
    *id = fc_client_next_request_id(c);
    fc_buf_reset(&c->tx);
    fc_code code = fc_wire_write_surface_request(&c->tx, *id, attributes, err);
    return code != FC_OK ? code : fc_client_send_tx(c, err);
}

/* Receives parts of reply `id` until the last; *cause keeps the first earlier rejection. */
static fc_code receive_parts(fc_client *c, uint32_t id, fc_surface_assembly *a, fc_error *cause, fc_error *err)
{
    bool complete = false;
    while (!complete) {
        fc_code code = fc_client_await_reply(c, id, FC_MSG_SURFACE_PART, cause, err);
        if (code != FC_OK)
            return code;
        fc_error why;
        if (fc_surface_assembly_add(a, c->rx.data, c->rx.len, &complete, &why) != FC_OK) {
            c->broken = true;
            return fc_error_set(err, FC_ERR_PROTOCOL, "bad SURFACE_PART from the server (%s): %s",
                                fc_code_name(why.code), why.message);
        }
    }
    return FC_OK;
}

static fc_code finish(fc_client *c, fc_surface_assembly *a, fc_surface_mesh *out, float *extract_ms, fc_error *err)
{
    fc_error why;
    fc_code code = fc_surface_assembly_finish(a, out, extract_ms, &why);
    if (code == FC_ERR_NOMEM)
        return fc_error_set(err, code, "%s", why.message);
    if (code != FC_OK) {
        c->broken = true;
        return fc_error_set(err, FC_ERR_PROTOCOL, "bad surface mesh from the server (%s): %s",
                            fc_code_name(why.code), why.message);
    }
    return FC_OK;
}

fc_code fc_client_extract_surface(fc_client *client, uint32_t attributes, fc_surface_mesh *out, float *extract_ms,
                                  fc_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_client_extract_surface needs a mesh to fill");
    uint32_t id;
    code = send_surface(client, attributes, &id, err);
    if (code != FC_OK)
        return code;

    fc_error cause, reply;
    fc_error_clear(&cause);
    fc_error_clear(&reply);
    fc_surface_assembly assembly;
    fc_surface_assembly_init(&assembly, 0);
    code = receive_parts(client, id, &assembly, &cause, &reply);
    if (code == FC_OK)
        code = finish(client, &assembly, out, extract_ms, &reply);
    fc_surface_assembly_free(&assembly);
    /* As for a render: an earlier rejection explains what the request used. */
    if (cause.code != FC_OK) {
        fc_surface_mesh_free(out);
        reply = cause;
        code = cause.code;
    }
    if (code != FC_OK && err)
        *err = reply;
    return code;
}
