/* view_link.h — the viewer's network worker: one thread owns the connection
 * to fluidcastd and does everything that waits on it (pushing frames, sending
 * the camera, rendering, receiving and decoding images), so the UI thread
 * never blocks on the network. At most one render is in flight: the worker
 * takes the newest request from the request slot when the previous image is
 * in, so a fast drag coalesces into the camera of its end.
 *
 * A double-click's pick renders a quarter-size depth AOV first and returns
 * the point under the cursor with the next image.
 *
 * Following a session, the worker tells the UI whether the session waits
 * (no frame yet), is live, or ended (fc_view_slots_set_session_state); after
 * the end it stays on the last frame, sending each view change at once and
 * reading back its re-rendered image (PROTOCOL.md 10.1).
 *
 * Images are asked for as RAW RGBA8 by default, so "decoding" is checking the
 * size and taking the rows; with --format jpeg or h264 they are decoded with
 * libavcodec on this thread (view_decode.h): a session's H.264 images as one
 * video stream, whose camera sizes are kept even (4:2:0). PNG is used for the
 * lossless screenshot, written as the server encoded it. */
#ifndef FC_VIEW_LINK_H
#define FC_VIEW_LINK_H

#include <pthread.h>
#include <stdbool.h>

#include "fluidcast.h"
#include "particle_reader.h"
#include "view_slot.h"

typedef struct fc_view_link_config {
    const char *session;          /* NULL: a sequence of files */
    const char *const *files;
    uint32_t file_count;
    fc_frame first_frame;         /* files[0], already read (the link takes it over) */
    const fc_read_options *read;  /* how the files are read (outlives the link) */
    bool log_camera;
    uint32_t width, height;       /* a session's first size, until a camera is sent */
    fc_image_format format;       /* RAW, JPEG or H264: how images travel */
    void (*wake)(void *ctx);      /* called after each image (thread-safe, quick) */
    void *wake_ctx;
} fc_view_link_config;

typedef struct fc_view_link {
    fc_view_link_config config;
    fc_view_slots *slots;
    fc_client *client;
    pthread_t thread;
    bool running;
    bool finished;                /* under slots->lock: the thread has returned */
} fc_view_link;

/* Starts the worker on an open client (the link closes it when it ends). */
fc_code fc_view_link_start(fc_view_link *link, const fc_view_link_config *config, fc_view_slots *slots,
                           fc_client *client, fc_error *err);

/* Asks the worker to stop and waits for it up to timeout_ms. False when it
 * is still waiting for a session's next image: it is left to the process's
 * exit, and the slots must then outlive this call (not be destroyed). */
bool fc_view_link_stop(fc_view_link *link, int timeout_ms);

#endif
