/* message_io.c — see message_io.h. */
#include "message_io.h"

#include "fc_error.h"
#include "socket_io.h"
#include "wire_session.h"

fc_code fc_message_receive(int fd, uint32_t max_payload, fc_msg_header *header, fc_buf *payload,
                           fc_error *err)
{
    uint8_t raw[FC_WIRE_HEADER_SIZE];
    fc_code code = fc_socket_recv_exact(fd, raw, sizeof raw, err);
    if (code != FC_OK)
        return code;
    fc_error why;
    if (fc_wire_decode_header(raw, max_payload, header, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_PROTOCOL, "bad message header from the server: %s", why.message);
    fc_buf_reset(payload);
    if (!fc_buf_reserve(payload, header->length))
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %u-byte %s from the server",
                            (unsigned)header->length, fc_message_type_name(header->type));
    code = fc_socket_recv_exact(fd, payload->data, header->length, err);
    if (code != FC_OK)
        return code;
    payload->len = header->length;
    return FC_OK;
}

const char *fc_message_type_name(uint16_t type)
{
    switch ((fc_msg_type)type) {
    case FC_MSG_HELLO: return "HELLO";
    case FC_MSG_WELCOME: return "WELCOME";
    case FC_MSG_FRAME: return "FRAME";
    case FC_MSG_CAMERA: return "CAMERA";
    case FC_MSG_SETTINGS: return "SETTINGS";
    case FC_MSG_RENDER: return "RENDER";
    case FC_MSG_IMAGE: return "IMAGE";
    case FC_MSG_ERROR: return "ERROR";
    case FC_MSG_GOODBYE: return "GOODBYE";
    }
    const char *session_message = fc_wire_session_type_name(type);
    return session_message ? session_message : "unknown message";
}
