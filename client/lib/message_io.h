/* message_io.h — receiving whole protocol messages on a client's channel. */
#ifndef FC_MESSAGE_IO_H
#define FC_MESSAGE_IO_H

#include <stdint.h>
#include "channel.h"
#include "wire.h"

/* Receives one message: its header into *header and its payload into `payload`
 * (reset first, capacity reused). A header that is not FCST or announces more
 * than max_payload bytes is FC_ERR_PROTOCOL; channel errors as fc_channel_recv_exact. */
fc_code fc_message_receive(fc_channel *ch, uint32_t max_payload, fc_msg_header *header, fc_buf *payload,
                           fc_error *err);

#endif
