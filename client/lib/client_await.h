/* client_await.h — waiting for the reply to a request, with a viewer's stream
 * messages arriving between the replies a client waits for. Below both the
 * requests (client_render.c, client_session.c) and the stream's own reading
 * (client_stream.c), so they all call down into it. Internal to the library. */
#ifndef FC_CLIENT_AWAIT_H
#define FC_CLIENT_AWAIT_H

#include <stdbool.h>

#include "client_core.h"

/* Takes a STREAM_IMAGE (dropped, counted as missed) or the session's
 * unsolicited SESSION_END (remembered for fc_client_next_image) that arrived
 * while the client waits for something else. False for any other message. */
bool fc_client_absorb_stream(fc_client *c, const fc_msg_header *header);

/* Waits for the reply of `type` to request `id`, leaving its payload in c->rx.
 * A server ERROR answering `id` is returned; the first ERROR answering an
 * earlier request is kept in *cause (the caller decides what it explains);
 * stream messages are absorbed. */
fc_code fc_client_await_reply(fc_client *c, uint32_t id, fc_msg_type type, fc_error *cause, fc_error *err);

#endif
