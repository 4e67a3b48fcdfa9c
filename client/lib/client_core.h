/* client_core.h — the client object shared by the libfluidcast sources, and the
 * steps every request is made of: numbering, sending, receiving, turning a
 * server ERROR into an fc_error. Internal to the library. */
#ifndef FC_CLIENT_CORE_H
#define FC_CLIENT_CORE_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast.h"
#include "fc_host_port.h"
#include "wire.h"

struct fc_client {
    int fd;
    char address[FC_HOST_MAX + 8];   /* the daemon connected to, "HOST:PORT" or "unix:PATH" (fc_client_address) */
    uint32_t last_request_id;
    uint32_t max_reply;        /* largest payload accepted from the server */
    bool broken;               /* the byte stream is lost or out of step: refuse further requests */
    fc_server_info info;
    fc_buf tx;                 /* encoded outgoing message, reused so frames do not reallocate */
    fc_buf rx;                 /* payload of the last incoming message, reused likewise */
    /* a viewer's stream (client_stream.c; what arrives while awaiting other replies: client_await.c) */
    bool subscribed;
    uint32_t subscribe_id;     /* request id of the SUBSCRIBE: its images and end echo it */
    uint32_t stream_skipped;   /* images dropped while waiting for other replies, not yet reported */
    bool stream_lost_unit;     /* an H.264 image was among them: a key frame is due (client_stream.c) */
    bool stream_ended;         /* the session's end arrived while waiting for something else, not yet reported */
    bool session_over;         /* the session's end was reported: still subscribed, only to its last frame */
};

/* FC_ERR_CLOSED once the connection is broken, FC_ERR_USAGE for a NULL client. */
fc_code fc_client_check_usable(const fc_client *c, fc_error *err);

/* The id for the next request; ids start at 1 and never repeat within 2^32 requests. */
uint32_t fc_client_next_request_id(fc_client *c);

/* FC_ERR_TOO_LARGE naming `what` when the message just encoded into c->tx
 * exceeds the server's limit: the server would drop the connection, so such a
 * message is refused unsent. */
fc_code fc_client_check_message_size(const fc_client *c, const char *what, fc_error *err);

/* Sends c->tx. A failure marks the client broken. */
fc_code fc_client_send_tx(fc_client *c, fc_error *err);

/* A FRAME without copying its particles: encodes the message's head into c->tx
 * and sends it followed by the frame's arrays from where the caller keeps them
 * (fc_wire_write_frame_parts), after fc_client_check_message_size's check of
 * the whole message. *wire_bytes (may be NULL) receives the bytes sent. */
fc_code fc_client_send_frame_message(fc_client *c, const fc_frame *frame, uint64_t *wire_bytes, fc_error *err);

/* Receives one message into *header and c->rx. A failure marks the client broken. */
fc_code fc_client_receive(fc_client *c, fc_msg_header *header, fc_error *err);

/* Decodes the ERROR payload in c->rx into *out: the server's code and its message
 * prefixed "server: ". A payload that does not decode is FC_ERR_PROTOCOL in *out
 * (and the client is marked broken). Returns out->code. */
fc_code fc_client_decode_server_error(fc_client *c, fc_error *out);

/* For an unexpected message: FC_ERR_PROTOCOL naming it and what was awaited;
 * marks the client broken. */
fc_code fc_client_unexpected(fc_client *c, const fc_msg_header *header, const char *awaited,
                             fc_error *err);

#endif
