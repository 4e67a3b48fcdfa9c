/* session.h — one named session: its producers (counted), its viewers,
 * the latest complete frame (latest wins: a frame nobody rendered yet is
 * simply replaced) and the multi-rank frames being assembled. Event-loop
 * thread only. */
#ifndef FC_DAEMON_SESSION_H
#define FC_DAEMON_SESSION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sessions/chunk_assembly.h"
#include "sessions/session_member.h"
#include "uploads/foam_track.h"
#include "uploads/mesh_uploads.h"
#include "uploads/shared_frame.h"
#include "wire_session.h"

typedef struct fc_session {
    char name[FC_SESSION_NAME_MAX + 1];
    uint32_t producers;
    bool had_producer;            /* losing the last producer ends the session only once there was one */
    bool ended;                   /* producers gone: it lives on, with its last frame, while it has viewers
                                     (they can still turn their cameras on it; PROTOCOL.md 10.1) */
    fc_session_member **viewers;  /* told of new frames and of the end (session_member.h) */
    size_t viewer_count;
    size_t viewer_capacity;
    fc_shared_frame *latest;      /* newest complete frame; NULL before the first */
    uint64_t sequence;            /* complete frames published so far */
    fc_foam_track *foam;          /* foam history of its frames, shared by every viewer */
    fc_chunk_assembly chunks;
    fc_mesh_set meshes;           /* its producers' MESHes, drawn in every viewer's images */
} fc_session;

struct fc_frame_pool;

fc_code fc_session_create(const char *name, struct fc_frame_pool *pool, fc_session **out,
                          fc_error *err);
void fc_session_destroy(fc_session *s);

void fc_session_describe(const fc_session *s, fc_session_info *out);
/* No producer and no viewer: nothing can reach it any more (an ended
 * session with viewers is still used: it keeps its last frame for them). */
bool fc_session_unused(const fc_session *s);

void fc_session_add_producer(fc_session *s);
/* The producer leaves; its pending chunks stay but it will not hear about them.
 * The last producer leaving ends the session: every viewer is told, and stays
 * on the last frame until it leaves. */
void fc_session_remove_producer(fc_session *s, const fc_session_member *producer);

fc_code fc_session_add_viewer(fc_session *s, fc_session_member *viewer, fc_error *err);
void fc_session_remove_viewer(fc_session *s, const fc_session_member *viewer);

/* Makes `frame` (whose reference is taken) the latest and tells every viewer. */
void fc_session_publish(fc_session *s, fc_shared_frame *frame);

#endif
