/* producer.c — how a simulation pushes its frames to fluidcastd: connect,
 * publish to a named session, then after each time step upload the particles
 * (zstd-compressed when the server can) and go on computing; viewers
 * (`fluidcast watch --session NAME`) see every frame they can keep up with.
 *
 *     fluidcast-example-producer [SERVER [SESSION [FRAMES]]]
 *
 * defaults: FC_DEFAULT_SERVER, "slosh", 96 frames. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "sloshing_block.h"

/* The example's stand-in for the solver's work between two frames. */
#define STEP_MS 30

static void compute_next_step(void)
{
    struct timespec pause = {0, STEP_MS * 1000000L};
    nanosleep(&pause, NULL);
}

/* Uploads `frames` frames; returns the first failure. */
static fc_code run(fc_client *c, uint32_t frames, fc_error *err)
{
    fc_server_info server;
    fc_client_server_info(c, &server);
    fc_upload_options upload = {.encoding = server.capabilities & FC_SERVER_CAN_ZSTD ? FC_UPLOAD_ZSTD : 0};
    uint64_t raw = 0, sent = 0;
    fc_code code = FC_OK;
    for (uint32_t step = 0; step < frames && code == FC_OK; step++) {
        fc_frame frame = {0};
        fc_upload_stats stats = {0};
        code = slosh_frame(step, 0.0f, SLOSH_TANK_LENGTH, &frame, err);
        if (code == FC_OK)
            code = fc_client_upload_frame(c, &frame, &upload, &stats, err);
        /* Rejections arrive asynchronously: look for them without waiting. */
        if (code == FC_OK)
            code = fc_client_poll_errors(c, err);
        raw += stats.raw_bytes;
        sent += stats.wire_bytes;
        fc_frame_free(&frame);
        compute_next_step();
    }
    if (code == FC_OK)
        printf("%u frames: %llu bytes sent for %llu bytes of particles\n", frames, (unsigned long long)sent,
               (unsigned long long)raw);
    return code;
}

int main(int argc, char **argv)
{
    const char *server = argc > 1 ? argv[1] : FC_DEFAULT_SERVER;
    const char *session = argc > 2 ? argv[2] : "slosh";
    uint32_t frames = argc > 3 ? (uint32_t)strtoul(argv[3], NULL, 10) : 96;
    fc_connect_options options = {.client_name = "example producer"};
    fc_client *c;
    fc_error err;
    if (fc_client_connect(server, &options, &c, &err) != FC_OK) {
        fprintf(stderr, "producer: %s\n", err.message);
        return 1;
    }
    fc_code code = fc_client_publish(c, session, NULL, &err);
    if (code == FC_OK)
        code = run(c, frames, &err);
    /* Leaving ends the session for its viewers, and waits for any late rejection. */
    if (code == FC_OK)
        code = fc_client_leave_session(c, &err);
    if (code != FC_OK)
        fprintf(stderr, "producer: %s: %s\n", fc_code_name(code), err.message);
    fc_client_close(c);
    return code == FC_OK ? 0 : 1;
}
