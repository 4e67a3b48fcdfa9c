/* render_job.h — one image to make: what the event loop asks the GL thread to
 * render and an encoder to encode, and what comes back (a complete IMAGE or
 * STREAM_IMAGE message, or an error). A job belongs to one thread at a time:
 * the loop fills it, the GL thread renders it, an encoder encodes it, the loop
 * delivers and frees it. */
#ifndef FC_DAEMON_RENDER_JOB_H
#define FC_DAEMON_RENDER_JOB_H

#include <stdbool.h>
#include <stdint.h>

#include "gpu/h264_stream.h"
#include "image.h"
#include "uploads/mesh_uploads.h"
#include "uploads/scene_uploads.h"
#include "uploads/shared_frame.h"
#include "wire.h"
#include "wire_session.h"

typedef enum fc_job_kind {
    FC_JOB_REPLY = 0,     /* answers a RENDER: an IMAGE, never dropped */
    FC_JOB_STREAM,        /* a viewer's STREAM_IMAGE */
    FC_JOB_SURFACE        /* answers a SURFACE: its SURFACE_PARTs, made on the GL thread, never encoded */
} fc_job_kind;

typedef struct fc_render_job {
    struct fc_render_job *next;      /* queue link */
    /* routing: who gets the result */
    uint64_t connection_id;
    uint32_t request_id;
    fc_job_kind kind;
    fc_stream_tag tag;               /* FC_JOB_STREAM only */
    fc_h264_stream *video;           /* an H.264 viewer's stream (a reference, dropped by fc_render_job_free);
                                        NULL: an H.264 image stands alone (RENDER) */
    bool force_keyframe;             /* the H.264 image must be an IDR frame */
    /* what to render */
    fc_shared_frame *frame;          /* one reference, dropped by fc_render_job_free */
    fc_camera camera;
    bool auto_camera;                /* frame the particles' bounds at camera.width x camera.height */
    fc_settings settings;
    fc_render_request request;
    uint32_t surface_attributes;     /* FC_JOB_SURFACE: the FC_SURFACE_* bits asked for */
    fc_scene_part *background;       /* the client's scene images: references, NULL = built-in */
    fc_scene_part *environment;
    fc_mesh_set meshes;              /* the meshes to draw, placed as at the request: references */
    /* timeline (fc_monotonic_ms) */
    double received_ms;              /* what FC_STAGE_TOTAL counts from */
    double submitted_ms;             /* queued for the GL thread */
    double rendered_ms;              /* queued for an encoder */
    float stage_ms[FC_STAGE_COUNT];
    /* results */
    fc_image image;                  /* read back by the GL thread, freed once encoded */
    fc_buf message;                  /* the complete reply message (FC_JOB_SURFACE: all its parts) */
    fc_error error;                  /* code != FC_OK: the job failed and `message` is empty */
} fc_render_job;

/* A zeroed job holding a reference to `frame`, every stage unmeasured. NULL when out of memory. */
fc_render_job *fc_render_job_create(fc_shared_frame *frame);
void fc_render_job_free(fc_render_job *job);
/* Frees a whole list linked through `next`. */
void fc_render_job_free_list(fc_render_job *list);

#endif
