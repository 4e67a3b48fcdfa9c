/* foam_apply.h — the GL thread's side of a stream's foam history
 * (uploads/foam_track.h): giving an uploaded frame its foam amplitudes. */
#ifndef FC_DAEMON_FOAM_APPLY_H
#define FC_DAEMON_FOAM_APPLY_H

#include "render/pipeline.h"
#include "uploads/shared_frame.h"

/* GL thread, right after `frame` was uploaded to `p`: a frame the GL thread
 * uploads for the first time advances its track with `settings` and keeps the
 * amplitudes that gave its particles; a frame uploaded again (another frame
 * was uploaded in between) gets those amplitudes back. */
fc_code fc_foam_apply(fc_shared_frame *frame, fc_pipeline *p, const fc_settings *settings, fc_error *err);

#endif
