/* e2e_stream.h — streaming: a producer publishes a session and pushes frames,
 * a viewer on its own connection and thread receives their images. */
#ifndef FC_E2E_STREAM_H
#define FC_E2E_STREAM_H

#include "e2e_scene.h"
#include "e2e_stats.h"

typedef struct e2e_stream_result {
    uint64_t pushed;          /* frames the producer sent */
    double push_seconds;      /* how long the producer pushed (at least the plan's seconds) */
    double push_fps;          /* pushed / push_seconds */
    uint64_t received;        /* new-frame images at the viewer (refresh and view images not counted) */
    uint64_t skipped;         /* sum of their `missed`: frames the server skipped for this viewer */
    int64_t in_flight;        /* pushed - received - skipped once the session ended (the protocol says 0) */
    double viewer_fps;        /* received / (last image or end of pushing, the later, - first push) */
    e2e_latency latency;      /* push start of a frame -> its image fully at the viewer */
} e2e_stream_result;

typedef struct e2e_stream_plan {
    const char *address;      /* the daemon */
    const char *session;      /* a name no one else uses */
    double seconds;           /* how long the producer pushes */
    double push_fps;          /* 0: as fast as the server accepts */
} e2e_stream_plan;

/* Subscribes the viewer, publishes, pushes for plan->seconds, leaves the
 * session and waits for the viewer to be told it ended. */
fc_code e2e_run_stream(const e2e_stream_plan *plan, const e2e_config *cfg, e2e_stream_result *out, fc_error *err);

#endif
