/* client_core.c — see client_core.h. */
#include "client_core.h"

#include "fc_error.h"
#include "message_io.h"

fc_code fc_client_check_usable(const fc_client *c, fc_error *err)
{
    if (!c)
        return fc_error_set(err, FC_ERR_USAGE, "no client given");
    if (c->broken)
        return fc_error_set(err, FC_ERR_CLOSED, "the connection was lost by an earlier failure; reconnect");
    return FC_OK;
}

uint32_t fc_client_next_request_id(fc_client *c)
{
    c->last_request_id++;
    if (c->last_request_id == 0)   /* 0 is left for messages that answer no request */
        c->last_request_id = 1;
    return c->last_request_id;
}

static fc_code check_payload_size(const fc_client *c, uint64_t payload, const char *what, fc_error *err)
{
    if (payload > c->info.max_message)
        return fc_error_set(err, FC_ERR_TOO_LARGE,
                            "%s of %llu bytes exceeds the server's message limit of %u bytes", what,
                            (unsigned long long)payload, (unsigned)c->info.max_message);
    return FC_OK;
}

fc_code fc_client_check_message_size(const fc_client *c, const char *what, fc_error *err)
{
    return check_payload_size(c, c->tx.len - FC_WIRE_HEADER_SIZE, what, err);
}

fc_code fc_client_send_tx(fc_client *c, fc_error *err)
{
    fc_code code = fc_channel_send_all(&c->channel, c->tx.data, c->tx.len, err);
    if (code != FC_OK)
        c->broken = true;
    return code;
}

fc_code fc_client_send_frame_message(fc_client *c, const fc_frame *frame, uint64_t *wire_bytes, fc_error *err)
{
    fc_buf_reset(&c->tx);
    fc_wire_span arrays[FC_WIRE_FRAME_ARRAYS];
    size_t count = 0;
    fc_code code = fc_wire_write_frame_parts(&c->tx, fc_client_next_request_id(c), frame, arrays, &count, err);
    if (code != FC_OK)
        return code;
    struct iovec parts[1 + FC_WIRE_FRAME_ARRAYS] = {{.iov_base = c->tx.data, .iov_len = c->tx.len}};
    uint64_t total = c->tx.len;
    for (size_t i = 0; i < count; i++) {
        parts[1 + i] = (struct iovec){.iov_base = (void *)arrays[i].data, .iov_len = arrays[i].size};
        total += arrays[i].size;
    }
    code = check_payload_size(c, total - FC_WIRE_HEADER_SIZE, "the frame", err);
    if (code != FC_OK)
        return code;
    code = fc_channel_send_parts(&c->channel, parts, 1 + count, err);
    if (code != FC_OK)
        c->broken = true;
    else if (wire_bytes)
        *wire_bytes = total;
    return code;
}

fc_code fc_client_receive(fc_client *c, fc_msg_header *header, fc_error *err)
{
    fc_code code = fc_message_receive(&c->channel, c->max_reply, header, &c->rx, err);
    if (code != FC_OK)
        c->broken = true;
    return code;
}

fc_code fc_client_decode_server_error(fc_client *c, fc_error *out)
{
    fc_error server;
    fc_error why;
    if (fc_wire_read_error(c->rx.data, c->rx.len, &server, &why) != FC_OK) {
        c->broken = true;
        return fc_error_set(out, FC_ERR_PROTOCOL, "malformed ERROR from the server: %s", why.message);
    }
    /* Only wire codes may travel; anything else would pass for success or a local failure. */
    if (server.code < 1 || server.code > 99) {
        c->broken = true;
        return fc_error_set(out, FC_ERR_PROTOCOL, "the server sent an ERROR with code %d, not a wire code",
                            (int)server.code);
    }
    return fc_error_set(out, server.code, "server: %s", server.message);
}

fc_code fc_client_unexpected(fc_client *c, const fc_msg_header *header, const char *awaited,
                             fc_error *err)
{
    c->broken = true;
    const char *name = fc_msg_name(header->type);
    return fc_error_set(err, FC_ERR_PROTOCOL,
                        "unexpected %s (type %u, request %u) from the server while waiting for %s",
                        name ? name : "message", (unsigned)header->type, (unsigned)header->request_id, awaited);
}
