/* client_await.c — see client_await.h. */
#include "client_await.h"

#include "fc_error.h"
#include "wire_session.h"

bool fc_client_absorb_stream(fc_client *c, const fc_msg_header *header)
{
    if (!c->subscribed || header->request_id != c->subscribe_id)
        return false;
    if (header->type == FC_MSG_STREAM_IMAGE) {
        fc_stream_tag tag;
        fc_image_reply image;
        fc_error why;
        /* The dropped image and the ones it had missed are all missed now. */
        if (fc_wire_read_stream_image(c->rx.data, c->rx.len, &tag, &image, &why) == FC_OK) {
            c->stream_skipped += tag.missed + 1;
            /* Later access units refer to this one: the decoder needs a key frame. */
            if (image.format == FC_FORMAT_H264)
                c->stream_lost_unit = true;
        }
        return true;
    }
    if (header->type == FC_MSG_SESSION_END) {
        c->stream_ended = true;
        return true;
    }
    return false;
}

fc_code fc_client_await_reply(fc_client *c, uint32_t id, fc_msg_type type, fc_error *cause, fc_error *err)
{
    for (;;) {
        fc_msg_header header;
        fc_code code = fc_client_receive(c, &header, err);
        if (code != FC_OK)
            return code;
        if (fc_client_absorb_stream(c, &header))
            continue;
        if (header.type == FC_MSG_ERROR) {
            fc_error server;
            fc_client_decode_server_error(c, &server);
            if (server.code == FC_ERR_PROTOCOL || header.request_id == id) {
                if (err)
                    *err = server;
                return server.code;
            }
            if (cause->code == FC_OK)
                *cause = server;
            continue;
        }
        if (header.type == type && header.request_id == id)
            return FC_OK;
        if (header.type == FC_MSG_GOODBYE) {
            c->broken = true;
            return fc_error_set(err, FC_ERR_CLOSED, "the server ended the connection (GOODBYE)");
        }
        return fc_client_unexpected(c, &header, fc_msg_name(type), err);
    }
}
