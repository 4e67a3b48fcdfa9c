/* viewer.h — the streaming side of a connection subscribed to a named session.
 * A viewer has at most one image in flight (rendering, encoding, or waiting in
 * the connection's output queue); while it has, newer frames simply replace
 * the one it would get next (latest wins) and are counted as missed. So a
 * slow viewer costs the GL thread one render per image it actually takes, and
 * never slows the producer or the other viewers. */
#ifndef FC_DAEMON_VIEWER_H
#define FC_DAEMON_VIEWER_H

#include <stdbool.h>
#include <stdint.h>

#include "gpu/h264_stream.h"
#include "gpu/render_job.h"
#include "wire_session.h"

struct fc_conversation;

typedef struct fc_viewer {
    uint32_t subscribe_id;         /* request id of the SUBSCRIBE: stream images and the end echo it */
    fc_render_request request;     /* format of the stream images */
    uint32_t auto_width;           /* size of the automatic camera (until a CAMERA arrives) */
    uint32_t auto_height;
    uint64_t last_sequence;        /* session sequence number of the last frame sent */
    fc_h264_stream *video;         /* H.264 streams: the viewer's encoder (one reference); NULL otherwise */
    bool keyframe_wanted;          /* H.264: the next image must be an IDR frame (an access unit was lost,
                                      or the client asked) */
    bool busy;                     /* an image is being made or still waits in the output queue */
    bool queued;                   /* ...and it has reached the output queue */
    size_t queued_bytes;           /* the size of that image's message */
    bool view_changed;             /* CAMERA or SETTINGS since the last image */
    double view_changed_ms;
    double refresh_due_ms;         /* when a lossless refresh of the shown frame is due; 0 = none */
    bool leaving;                  /* the client sent SESSION_END: the answer goes out once nothing is in flight */
    uint32_t end_request_id;       /* ...that SESSION_END's request id */
    bool told_ended;               /* the session ended and this viewer got its SESSION_END: it stays, and
                                      only its own CAMERA/SETTINGS (and their REFRESH) make images */
} fc_viewer;

/* Subscribes the conversation (already added to c->session as a viewer) with
 * request id `subscribe_id`; a frame the session has already is sent at once. */
void fc_viewer_start(struct fc_conversation *c, uint32_t subscribe_id, const fc_subscribe *sub, uint32_t auto_width,
                     uint32_t auto_height);
/* CAMERA or SETTINGS changed: the current frame is rendered again for this viewer. */
void fc_viewer_view_changed(struct fc_conversation *c, double now_ms);
/* The client asked for a key frame (an empty SETTINGS, PROTOCOL.md 10.7): an
 * H.264 viewer's next image is an IDR frame; the current frame is sent again
 * as one. Other viewers just get the current frame again. */
void fc_viewer_keyframe_requested(struct fc_conversation *c, double now_ms);
/* The client sent SESSION_END: no more images; SESSION_END answers request_id
 * once the image in flight (if any) has gone out. */
void fc_viewer_leave(struct fc_conversation *c, uint32_t request_id);
/* A stream job of this viewer finished: queue its image (or its ERROR). */
void fc_viewer_job_done(struct fc_conversation *c, const fc_render_job *job);
/* The connection's output queue is empty. */
void fc_viewer_drained(struct fc_conversation *c);
/* How much of its output the kernel may still hold before the viewer's next
 * image starts: about one image (so a link stays busy), SIZE_MAX when no image waits. */
size_t fc_viewer_backlog_allowance(const struct fc_conversation *c);
/* When the viewer next needs fc_viewer_tick without I/O; negative for never. */
double fc_viewer_deadline_ms(const struct fc_conversation *c);
void fc_viewer_tick(struct fc_conversation *c, double now_ms);
/* Leaves the named session without a word to the client (SESSION_END went
 * out already, the client has gone, or the caller answers). */
void fc_viewer_detach(struct fc_conversation *c);

/* What the named session tells a viewer, through the conversation's member
 * (conversation_sessions.c): the session published a new frame; */
void fc_viewer_on_new_frame(struct fc_conversation *c);
/* the session lost its last producer: the viewer gets what is pending, then
 * SESSION_END, and stays on the last frame (PROTOCOL.md 10.1). */
void fc_viewer_on_session_ended(struct fc_conversation *c);
/* The viewer is in a session that ended and has been told so: a SUBSCRIBE or
 * PUBLISH leaves that session first, without a word (it had its SESSION_END). */
bool fc_viewer_in_ended_session(const struct fc_conversation *c);

#endif
