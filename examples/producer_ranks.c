/* producer_ranks.c — how an MPI-parallel simulation pushes its frames: each of
 * K ranks (here a thread each, standing in for MPI processes) connects on its
 * own, publishes to the same session, and after every time step sends its own
 * particles as chunk `rank` of K of the frame. The server renders a frame once
 * all K chunks are in, exactly as if it had been sent whole.
 *
 *     fluidcast-example-producer_ranks [SERVER [SESSION [FRAMES [RANKS]]]]
 *
 * defaults: FC_DEFAULT_SERVER, "slosh", 96 frames, 4 ranks. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "sloshing_block.h"

#define MAX_RANKS 64

typedef struct rank {
    const char *server;
    const char *session;
    uint32_t frames;
    uint32_t index;
    uint32_t count;
    pthread_barrier_t *step_done;   /* MPI_Barrier stand-in: ranks advance in lock step */
    fc_error err;
    fc_code code;
} rank;

/* This rank's slab of the tank: x in [index, index + 1) * length / count. */
static fc_code send_step(fc_client *c, const rank *r, uint32_t step, const fc_upload_options *upload,
                         fc_error *err)
{
    float width = SLOSH_TANK_LENGTH / (float)r->count;
    fc_frame part = {0};
    fc_code code = slosh_frame(step, width * (float)r->index, width * (float)(r->index + 1), &part, err);
    /* Frame numbers start at 1; every rank uses the same number for the same step. */
    if (code == FC_OK)
        code = fc_client_send_chunk(c, step + 1, r->index, r->count, &part, upload, NULL, err);
    if (code == FC_OK)
        code = fc_client_poll_errors(c, err);
    fc_frame_free(&part);
    return code;
}

static void *rank_main(void *arg)
{
    rank *r = arg;
    char name[32];
    snprintf(name, sizeof name, "example rank %u", r->index);
    fc_connect_options options = {.client_name = name};
    fc_client *c = NULL;
    r->code = fc_client_connect(r->server, &options, &c, &r->err);
    if (r->code == FC_OK)
        r->code = fc_client_publish(c, r->session, NULL, &r->err);
    fc_upload_options upload = {.encoding = FC_UPLOAD_ZSTD};
    for (uint32_t step = 0; step < r->frames; step++) {
        /* A failed rank keeps meeting the barrier, so the others are not left waiting. */
        if (r->code == FC_OK)
            r->code = send_step(c, r, step, &upload, &r->err);
        pthread_barrier_wait(r->step_done);
    }
    if (r->code == FC_OK)
        r->code = fc_client_leave_session(c, &r->err);
    fc_client_close(c);
    return NULL;
}

int main(int argc, char **argv)
{
    rank ranks[MAX_RANKS];
    pthread_t threads[MAX_RANKS];
    pthread_barrier_t step_done;
    uint32_t count = argc > 4 ? (uint32_t)strtoul(argv[4], NULL, 10) : 4;
    if (count < 1 || count > MAX_RANKS) {
        fprintf(stderr, "producer_ranks: 1 to %d ranks\n", MAX_RANKS);
        return 2;
    }
    pthread_barrier_init(&step_done, NULL, count);
    for (uint32_t i = 0; i < count; i++) {
        memset(&ranks[i], 0, sizeof ranks[i]);
        ranks[i].server = argc > 1 ? argv[1] : FC_DEFAULT_SERVER;
        ranks[i].session = argc > 2 ? argv[2] : "slosh";
        ranks[i].frames = argc > 3 ? (uint32_t)strtoul(argv[3], NULL, 10) : 96;
        ranks[i].index = i;
        ranks[i].count = count;
        ranks[i].step_done = &step_done;
        pthread_create(&threads[i], NULL, rank_main, &ranks[i]);
    }
    int status = 0;
    for (uint32_t i = 0; i < count; i++) {
        pthread_join(threads[i], NULL);
        if (ranks[i].code != FC_OK) {
            fprintf(stderr, "rank %u: %s: %s\n", i, fc_code_name(ranks[i].code), ranks[i].err.message);
            status = 1;
        }
    }
    pthread_barrier_destroy(&step_done);
    if (status == 0)
        printf("%u ranks sent %u frames\n", count, ranks[0].frames);
    return status;
}
