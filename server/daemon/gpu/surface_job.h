/* surface_job.h — a SURFACE request on the GL thread: the frame's surface
 * extracted by the render pipeline (render/surface_extract.h) and written out
 * as the SURFACE_PART messages of the reply (PROTOCOL.md 13). */
#ifndef FC_DAEMON_SURFACE_JOB_H
#define FC_DAEMON_SURFACE_JOB_H

#include "gpu/render_job.h"
#include "render/pipeline.h"

/* Extracts the surface of job->frame with job->settings (radius resolved to
 * `radius`), keeps the attributes job->surface_attributes asks for and fills
 * job->message with every part of the reply. The extractor's codes (LIMIT, GL,
 * NOMEM), or LIMIT for a mesh beyond what one reply carries. */
fc_code fc_surface_job_run(fc_pipeline *pipeline, fc_render_job *job, float radius, fc_error *err);

#endif
