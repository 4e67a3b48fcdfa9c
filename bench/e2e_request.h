/* e2e_request.h — request/response: frame + RENDER, timed from the start of
 * the send until the image is fully received. */
#ifndef FC_E2E_REQUEST_H
#define FC_E2E_REQUEST_H

#include "e2e_scene.h"
#include "e2e_stats.h"
#include "fluidcast.h"

typedef struct e2e_request_result {
    int answered;                     /* requests that came back with an image */
    e2e_latency latency;
    double image_kib;                 /* mean encoded image size */
    double stage_ms[FC_STAGE_COUNT];  /* mean of the server's stage times; negative: not measured */
} e2e_request_result;

/* One untimed request (the first render at a new size or particle count
 * allocates GPU buffers), then `requests` timed ones, each with a nudged frame. */
fc_code e2e_run_requests(fc_client *client, const e2e_config *cfg, int requests, e2e_request_result *out,
                         fc_error *err);

#endif
