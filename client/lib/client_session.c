/* client_session.c — joining, leaving and listing named sessions. */
#include "fluidcast.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client_await.h"
#include "fc_error.h"
#include "wire_session.h"

_Static_assert(FC_SERVER_CAN_STREAM == FC_CAP_SESSIONS && FC_SERVER_CAN_ZSTD == FC_CAP_ZSTD &&
                   FC_SERVER_CAN_QUANTIZE16 == FC_CAP_QUANTIZE16,
               "fluidcast.h capability bits must match the wire's");
_Static_assert(sizeof(((fc_session_status *)0)->name) == FC_SESSION_NAME_MAX + 1,
               "fc_session_status.name must hold a wire session name");

static void copy_status(const fc_session_info *info, fc_session_status *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", info->name);
    out->producers = info->producers;
    out->viewers = info->viewers;
    out->frames = info->frames;
    out->last_frame = info->last_frame;
}

static fc_code check_streaming(const fc_client *c, fc_error *err)
{
    fc_code code = fc_client_check_usable(c, err);
    if (code == FC_OK && !(c->info.capabilities & FC_SERVER_CAN_STREAM))
        return fc_error_set(err, FC_ERR_USAGE, "the server did not grant sessions (capability 0x%x)",
                            FC_SERVER_CAN_STREAM);
    return code;
}

/* Sends c->tx (request `id`) and waits for its reply of `type`. An earlier
 * request's rejection, when one arrives on the way, is returned instead, as
 * it is the cause (as fc_client_render does). */
static fc_code exchange(fc_client *c, uint32_t id, fc_msg_type type, fc_error *err)
{
    fc_code code = fc_client_send_tx(c, err);
    if (code != FC_OK)
        return code;
    fc_error cause;
    fc_error_clear(&cause);
    code = fc_client_await_reply(c, id, type, &cause, err);
    if (cause.code == FC_OK)
        return code;
    if (err)
        *err = cause;
    return cause.code;
}

/* Reads the SESSION_STATE in c->rx into *status (when given). */
static fc_code take_state(fc_client *c, fc_session_status *status, fc_error *err)
{
    fc_session_info info;
    fc_error why;
    if (fc_wire_read_session_state(c->rx.data, c->rx.len, &info, &why) != FC_OK) {
        c->broken = true;
        return fc_error_set(err, FC_ERR_PROTOCOL, "malformed SESSION_STATE from the server: %s", why.message);
    }
    if (status)
        copy_status(&info, status);
    return FC_OK;
}

fc_code fc_client_publish(fc_client *client, const char *name, fc_session_status *status, fc_error *err)
{
    fc_code code = check_streaming(client, err);
    if (code != FC_OK)
        return code;
    uint32_t id = fc_client_next_request_id(client);
    fc_buf_reset(&client->tx);
    code = fc_wire_write_publish(&client->tx, id, name, err);
    if (code == FC_OK)
        code = exchange(client, id, FC_MSG_SESSION_STATE, err);
    return code != FC_OK ? code : take_state(client, status, err);
}

fc_code fc_client_subscribe(fc_client *client, const char *name, const fc_render_request *format,
                            uint32_t width, uint32_t height, fc_session_status *status, fc_error *err)
{
    fc_code code = check_streaming(client, err);
    if (code != FC_OK)
        return code;
    if (!format || !name || strlen(name) > FC_SESSION_NAME_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "fc_client_subscribe needs a format and a name of 1..%u bytes",
                            FC_SESSION_NAME_MAX);
    fc_subscribe sub;
    memset(&sub, 0, sizeof sub);
    sub.request = *format;
    sub.width = width;
    sub.height = height;
    snprintf(sub.name, sizeof sub.name, "%s", name);
    uint32_t id = fc_client_next_request_id(client);
    fc_buf_reset(&client->tx);
    code = fc_wire_write_subscribe(&client->tx, id, &sub, err);
    if (code == FC_OK)
        code = exchange(client, id, FC_MSG_SESSION_STATE, err);
    if (code != FC_OK)
        return code;
    client->subscribed = true;
    client->subscribe_id = id;
    client->stream_skipped = 0;
    client->stream_ended = false;
    client->session_over = false;
    return take_state(client, status, err);
}

/* A server before PROTOCOL.md 10.1's "viewers stay on the last frame" had
 * dropped the viewer with its SESSION_END and refuses the leave as BAD_STATE:
 * the viewer is out either way. */
static bool ended_before_leave(const fc_client *c, fc_code code)
{
    return code == FC_ERR_BAD_STATE && c->subscribed && (c->stream_ended || c->session_over);
}

fc_code fc_client_leave_session(fc_client *client, fc_error *err)
{
    fc_code code = check_streaming(client, err);
    if (code != FC_OK)
        return code;
    uint32_t id = fc_client_next_request_id(client);
    fc_buf_reset(&client->tx);
    code = fc_wire_write_session_leave(&client->tx, id, err);
    if (code == FC_OK)
        code = exchange(client, id, FC_MSG_SESSION_END, err);
    if (ended_before_leave(client, code)) {
        if (err)
            fc_error_clear(err);
        code = FC_OK;
    }
    if (code == FC_OK || !client->broken) {
        client->subscribed = false;
        client->stream_ended = false;
        client->session_over = false;
    }
    return code;
}

int fc_client_session_ended(const fc_client *client)
{
    return client && client->subscribed && (client->stream_ended || client->session_over);
}

fc_code fc_client_list_sessions(fc_client *client, fc_session_status **sessions, uint32_t *count, fc_error *err)
{
    if (sessions)
        *sessions = NULL;
    if (count)
        *count = 0;
    fc_code code = check_streaming(client, err);
    if (code != FC_OK)
        return code;
    if (!sessions || !count)
        return fc_error_set(err, FC_ERR_USAGE, "fc_client_list_sessions needs somewhere to put the list");
    uint32_t id = fc_client_next_request_id(client);
    fc_buf_reset(&client->tx);
    code = fc_wire_write_list_sessions(&client->tx, id, err);
    if (code == FC_OK)
        code = exchange(client, id, FC_MSG_SESSION_LIST, err);
    if (code != FC_OK)
        return code;
    fc_session_info *infos;
    uint32_t n;
    fc_error why;
    if (fc_wire_read_session_list(client->rx.data, client->rx.len, &infos, &n, &why) != FC_OK) {
        client->broken = true;
        return fc_error_set(err, FC_ERR_PROTOCOL, "malformed SESSION_LIST from the server: %s", why.message);
    }
    fc_session_status *list = calloc(n ? n : 1, sizeof *list);
    if (!list) {
        free(infos);
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for %u sessions", n);
    }
    for (uint32_t i = 0; i < n; i++)
        copy_status(&infos[i], &list[i]);
    free(infos);
    *sessions = list;
    *count = n;
    return FC_OK;
}

void fc_session_list_free(fc_session_status *sessions)
{
    free(sessions);
}
