/* chunk_assembly.h — putting multi-rank frames together: a simulation split
 * over K ranks sends frame f as K chunks over K connections; once all K are
 * in, their particles are concatenated in chunk index order. Pure bookkeeping
 * on the event-loop thread: no sockets, no GL. */
#ifndef FC_DAEMON_CHUNK_ASSEMBLY_H
#define FC_DAEMON_CHUNK_ASSEMBLY_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "sessions/session_member.h"
#include "wire_session.h"

/* Frames of one session being assembled at once (ranks drift apart by a frame or two). */
#define FC_ASSEMBLY_MAX_FRAMES 8

struct fc_frame_pool;

/* Who sent a chunk, to be told when its frame fails. */
typedef struct fc_chunk_origin {
    fc_session_member *producer;  /* NULL once that producer has gone */
    uint32_t request_id;
} fc_chunk_origin;

/* One received chunk: its particles (moved into the assembly) and timing. */
typedef struct fc_chunk {
    fc_chunk_header header;
    fc_frame_view part;           /* its block is moved into the assembly */
    fc_chunk_origin origin;
    double first_byte_ms;         /* when its message started to arrive */
    double received_ms;           /* when its last byte arrived */
    float decode_ms;              /* decoding it took */
} fc_chunk;

typedef struct fc_frame_assembly {
    bool used;
    uint64_t frame_number;
    uint32_t count;               /* K */
    uint32_t received;
    uint32_t attributes;
    uint64_t particles;
    fc_frame_view *parts;         /* K slots; frame.count == 0 while missing */
    fc_chunk_origin *origins;     /* K slots */
    double deadline_ms;
    double first_byte_ms, last_byte_ms;
    float decode_ms;
} fc_frame_assembly;

typedef struct fc_chunk_assembly {
    struct fc_frame_pool *pool;   /* the parts' and the whole frames' blocks */
    fc_frame_assembly frames[FC_ASSEMBLY_MAX_FRAMES];
    bool any_completed;
    uint64_t last_completed;      /* frame number of the newest completed frame */
} fc_chunk_assembly;

/* A frame that just completed. */
typedef struct fc_assembled_frame {
    fc_frame_view frame;          /* in a block from the pool */
    uint64_t frame_number;
    float receive_ms;             /* first byte of the first chunk -> last byte of the last */
    float decode_ms;              /* decoding every chunk plus concatenating them */
} fc_assembled_frame;

void fc_chunk_assembly_init(fc_chunk_assembly *a, struct fc_frame_pool *pool);
void fc_chunk_assembly_free(fc_chunk_assembly *a);

/* Adds a chunk. Refused (chunk->part untouched, *complete false): INVALID_VALUE
 * for K = 0, K > FC_CHUNK_COUNT_MAX or index >= K; INCONSISTENT when K or the
 * attributes differ from the frame's first chunk; DUPLICATE when this index of
 * the frame arrived already or the frame completed already; BAD_STATE for a
 * frame older than the newest completed one; LIMIT when the particles exceed
 * max_particles or FC_ASSEMBLY_MAX_FRAMES frames are open. Accepted: the part
 * is taken; when it was the last one, *complete is true and *out holds the
 * whole frame. */
fc_code fc_chunk_assembly_add(fc_chunk_assembly *a, fc_chunk *chunk, uint64_t max_particles, double now_ms,
                              double timeout_ms, bool *complete, fc_assembled_frame *out, fc_error *err);

/* Earliest deadline of an open frame, or a negative value when none is open. */
double fc_chunk_assembly_next_deadline(const fc_chunk_assembly *a);

/* Discards every frame whose deadline has passed, calling report(origin, err)
 * (FC_ERR_INCOMPLETE) for each chunk it had received from a connection still there. */
void fc_chunk_assembly_expire(fc_chunk_assembly *a, double now_ms,
                              void (*report)(const fc_chunk_origin *origin, const fc_error *err, void *data),
                              void *data);

/* The producer has gone: its chunks stay, but nobody is told about them. */
void fc_chunk_assembly_forget(fc_chunk_assembly *a, const fc_session_member *producer);

#endif
