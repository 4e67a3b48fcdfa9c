/* client_stream.c — a viewer's images, and the server's rejections read
 * between requests (fc_client_poll_errors). */
#include "fluidcast.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "client_await.h"
#include "fc_error.h"
#include "wire_session.h"

/* Copies the STREAM_IMAGE in c->rx into *out, which then owns its bytes. */
static fc_code take_stream_image(fc_client *c, fc_stream_image *out, fc_error *err)
{
    fc_stream_tag tag;
    fc_image_reply reply;
    fc_error why;
    if (fc_wire_read_stream_image(c->rx.data, c->rx.len, &tag, &reply, &why) != FC_OK) {
        c->broken = true;
        return fc_error_set(err, FC_ERR_PROTOCOL, "malformed STREAM_IMAGE from the server: %s", why.message);
    }
    uint8_t *data = malloc(reply.size ? (size_t)reply.size : 1);
    if (!data)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %llu-byte image", (unsigned long long)reply.size);
    memcpy(data, reply.data, (size_t)reply.size);
    out->image.width = reply.width;
    out->image.height = reply.height;
    out->image.format = reply.format;
    out->image.aov = reply.aov;
    memcpy(out->image.stage_ms, reply.stage_ms, sizeof out->image.stage_ms);
    out->image.data = data;
    out->image.size = (size_t)reply.size;
    out->frame_number = tag.frame_number;
    out->sequence = tag.sequence;
    out->missed = tag.missed + c->stream_skipped;
    out->refresh = (tag.flags & FC_STREAM_REFRESH) != 0;
    out->view_change = (tag.flags & FC_STREAM_VIEW) != 0;
    out->keyframe = (tag.flags & FC_STREAM_KEYFRAME) != 0;
    c->stream_skipped = 0;
    return FC_OK;
}

fc_code fc_client_request_keyframe(fc_client *client, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!client->subscribed)
        return fc_error_set(err, FC_ERR_USAGE, "this client is not subscribed to a session");
    fc_buf_reset(&client->tx);
    code = fc_wire_write_settings_none(&client->tx, fc_client_next_request_id(client), err);
    return code != FC_OK ? code : fc_client_send_tx(client, err);
}

/* An H.264 unit was dropped: asks for a key frame once the stream goes on
 * without one (the request is sent between messages, so it cannot interleave). */
static fc_code recover_lost_unit(fc_client *c, const fc_stream_image *image, fc_error *err)
{
    if (!c->stream_lost_unit || image->image.format != FC_FORMAT_H264)
        return FC_OK;
    c->stream_lost_unit = false;
    return image->keyframe ? FC_OK : fc_client_request_keyframe(c, err);
}

/* The session ended; the viewer stays subscribed to its last frame (PROTOCOL.md 10.1). */
static void end_of_stream(fc_client *c, fc_stream_image *out)
{
    out->ended = 1;
    out->missed = c->stream_skipped;
    c->stream_ended = false;
    c->session_over = true;
    c->stream_skipped = 0;
}

fc_code fc_client_next_image(fc_client *client, fc_stream_image *out, fc_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_client_next_image needs somewhere to put the image");
    if (!client->subscribed)
        return fc_error_set(err, FC_ERR_USAGE, "this client is not subscribed to a session");
    if (client->stream_ended) {
        end_of_stream(client, out);
        return FC_OK;
    }
    for (;;) {
        fc_msg_header header;
        code = fc_client_receive(client, &header, err);
        if (code != FC_OK)
            return code;
        bool ours = header.request_id == client->subscribe_id;
        if (header.type == FC_MSG_STREAM_IMAGE && ours) {
            code = take_stream_image(client, out, err);
            return code != FC_OK ? code : recover_lost_unit(client, out, err);
        }
        if (header.type == FC_MSG_SESSION_END && ours) {
            end_of_stream(client, out);
            return FC_OK;
        }
        if (header.type == FC_MSG_ERROR)
            return fc_client_decode_server_error(client, err);
        if (header.type == FC_MSG_GOODBYE) {
            client->broken = true;
            return fc_error_set(err, FC_ERR_CLOSED, "the server ended the connection (GOODBYE)");
        }
        return fc_client_unexpected(client, &header, fc_msg_name(FC_MSG_STREAM_IMAGE), err);
    }
}

void fc_stream_image_free(fc_stream_image *image)
{
    if (!image)
        return;
    fc_image_result_free(&image->image);
    memset(image, 0, sizeof *image);
}

fc_code fc_client_wait_input(fc_client *client, uint32_t timeout_ms, int *ready, fc_error *err)
{
    if (ready)
        *ready = 0;
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!ready)
        return fc_error_set(err, FC_ERR_USAGE, "fc_client_wait_input needs somewhere to say whether input waits");
    int wait = timeout_ms > INT_MAX ? INT_MAX : (int)timeout_ms;
    *ready = client->stream_ended || fc_channel_wait_input(&client->channel, wait);
    return FC_OK;
}

fc_code fc_client_poll_errors(fc_client *client, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    while (code == FC_OK && fc_channel_wait_input(&client->channel, 0)) {
        fc_msg_header header;
        code = fc_client_receive(client, &header, err);
        if (code != FC_OK || fc_client_absorb_stream(client, &header))
            continue;
        if (header.type == FC_MSG_ERROR)
            return fc_client_decode_server_error(client, err);
        if (header.type == FC_MSG_GOODBYE) {
            client->broken = true;
            return fc_error_set(err, FC_ERR_CLOSED, "the server ended the connection (GOODBYE)");
        }
        return fc_client_unexpected(client, &header, "nothing", err);
    }
    return code;
}
