/* message_io.c — see message_io.h. */
#include "message_io.h"

#include "fc_error.h"

fc_code fc_message_receive(fc_channel *ch, uint32_t max_payload, fc_msg_header *header, fc_buf *payload,
                           fc_error *err)
{
    uint8_t raw[FC_WIRE_HEADER_SIZE];
    fc_code code = fc_channel_recv_exact(ch, raw, sizeof raw, err);
    if (code != FC_OK)
        return code;
    fc_error why;
    if (fc_wire_decode_header(raw, max_payload, header, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_PROTOCOL, "bad message header from the server: %s", why.message);
    fc_buf_reset(payload);
    if (!fc_buf_reserve(payload, header->length))
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %u-byte message (type %u) from the server",
                            (unsigned)header->length, (unsigned)header->type);
    code = fc_channel_recv_exact(ch, payload->data, header->length, err);
    if (code != FC_OK)
        return code;
    payload->len = header->length;
    return FC_OK;
}
