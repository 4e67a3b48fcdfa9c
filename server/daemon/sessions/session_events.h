/* session_events.h — what a named session tells the connections in it. The
 * session and registry code call these; the clients implement them. */
#ifndef FC_DAEMON_SESSION_EVENTS_H
#define FC_DAEMON_SESSION_EVENTS_H

#include "sessions/chunk_assembly.h"

struct fc_client;

/* A viewer's session published a new frame. */
void fc_client_on_new_frame(struct fc_client *viewer);

/* A viewer's session lost its last producer: the viewer gets what is pending, then SESSION_END. */
void fc_client_on_session_ended(struct fc_client *viewer);

/* A multi-rank frame this producer sent a chunk of failed (FC_ERR_INCOMPLETE):
 * the ERROR answers that chunk. `data` is unused. */
void fc_client_on_chunk_failed(const fc_chunk_origin *origin, const fc_error *err, void *data);

#endif
