/* session_registry.h — the daemon's named sessions: finding or creating one by
 * name, listing them, and the chunk timeouts across all of them. Event-loop
 * thread only; owned by the daemon's top level (no global state). */
#ifndef FC_DAEMON_SESSION_REGISTRY_H
#define FC_DAEMON_SESSION_REGISTRY_H

#include <stddef.h>
#include <stdint.h>

#include "sessions/session.h"

typedef struct fc_session_registry fc_session_registry;

struct fc_frame_pool;

/* pool: where the sessions' chunk blocks come from and go back to. */
/* How many named sessions exist. */
size_t fc_registry_count(const fc_session_registry *reg);

fc_code fc_registry_create(uint32_t max_sessions, struct fc_frame_pool *pool, fc_session_registry **out,
                           fc_error *err);
/* Frees every session. The connections in them must be gone already. */
void fc_registry_destroy(fc_session_registry *reg);

/* The live (not ended) session called `name`, created when there is none
 * (an ended one of that name stays apart, for its viewers). FC_ERR_LIMIT when
 * max_sessions exist already, ended ones with viewers counted. */
fc_code fc_registry_open(fc_session_registry *reg, const char *name, fc_session **out, fc_error *err);
/* Frees every session that has neither producers nor viewers any more. Called
 * by the event loop between events, or by a conversation's message handler
 * that just left an ended session (so its place counts for the next), never
 * from inside a session's callbacks, so no session disappears under code
 * still using it. */
void fc_registry_collect(fc_session_registry *reg);

/* The live sessions, oldest first, in a malloc'd array (free() it). */
fc_code fc_registry_list(const fc_session_registry *reg, fc_session_info **out, uint32_t *count, fc_error *err);

/* Earliest chunk deadline of any session, negative when none. */
double fc_registry_next_deadline(const fc_session_registry *reg);
/* Fails every multi-rank frame whose deadline has passed (see fc_chunk_assembly_expire). */
void fc_registry_expire(fc_session_registry *reg, double now_ms);

#endif
