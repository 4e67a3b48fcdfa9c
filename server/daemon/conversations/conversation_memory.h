/* conversation_memory.h — the one place that accounts what a connection holds on
 * the daemon, against --max-session-memory (PROTOCOL.md 6.4). What it holds
 * is measured from its state each time it asks for more, so there is no
 * counter that could drift from the truth:
 *
 *   - its own frame (the last FRAME of a connection outside named sessions);
 *   - its scene images (background, cube-map faces), decoded;
 *   - the replies queued for it that the socket has not taken yet;
 *   - its TLS session, a fixed estimate (FC_TLS_SESSION_BYTES, net/transport.h);
 *   - for an H.264 viewer, its stream's encoder, estimated for its image size
 *     (fc_h264_stream_memory);
 *   - for a producer, its named session's latest frame and every chunk of the
 *     multi-rank frames being assembled: each producer answers for all of it,
 *     as any of them may complete it.
 *
 * A frame counts its particle arrays plus the noise amplitude the GL thread
 * keeps per particle once it renders it; a chunk counts likewise, as its share
 * of the frame it will form. Not counted: the message being received (bounded
 * by max_message), the one render a connection has in flight, what the GL
 * thread keeps (the foam history, copies on the GPU), the blocks the frame
 * pool keeps for reuse (daemon memory, bounded there: frame_pool.h), and
 * what a frame or chunk decoded in place keeps beyond its arrays with its
 * message's buffer: at most 64 bytes and an eighth (fc_conversation_keep_payload).
 * Event-loop thread only. */
#ifndef FC_DAEMON_CONVERSATION_MEMORY_H
#define FC_DAEMON_CONVERSATION_MEMORY_H

#include <stdint.h>

#include "conversations/conversation.h"

uint64_t fc_memory_of_frame(const fc_frame *frame);
uint64_t fc_memory_of_scene_part(const fc_scene_part *part);   /* 0 for NULL */

/* An H.264 viewer's encoder at width x height (0 for other formats): what
 * SUBSCRIBE and a viewer's CAMERA admit. */
uint64_t fc_memory_of_video(fc_image_format format, uint32_t width, uint32_t height);

/* Everything the list above counts for this connection. */
uint64_t fc_conversation_memory_held(const fc_conversation *c);

/* FC_OK when the conversation, giving up `released` bytes of what it holds and
 * taking `added` more, stays within its limit; else FC_ERR_LIMIT with a reason
 * that names `what` (e.g. "a frame of 1000 particles") and the limit. */
fc_code fc_conversation_memory_admit(const fc_conversation *c, uint64_t released, uint64_t added, const char *what,
                                     fc_error *err);

#endif
