/* e2e_options.h — the command line of fluidcast-e2e-bench. */
#ifndef FC_E2E_OPTIONS_H
#define FC_E2E_OPTIONS_H

#include "fluidcast_types.h"

#define E2E_MAX_LIST 8

typedef struct e2e_options {
    int help;
    const char *server;           /* --server HOST:PORT; NULL: start a daemon */
    const char *daemon_path;      /* --daemon; NULL: the fluidcastd built with it */
    const char *gpu;              /* --gpu software|auto, passed to the daemon */
    uint64_t particles[E2E_MAX_LIST];
    int n_particles;
    uint32_t sizes[E2E_MAX_LIST][2];
    int n_sizes;
    fc_image_format formats[E2E_MAX_LIST];
    int n_formats;
    uint32_t quality;             /* JPEG quality */
    int requests;                 /* timed requests per configuration; 0 = no request/response part */
    double stream_seconds;        /* producer run per configuration; 0 = no streaming part */
    double push_fps;              /* producer rate; 0 = as fast as the server accepts */
    int density;                  /* --density: frames carry a density per particle, as SPH codes send */
    fc_jpeg_subsampling stream_subsampling; /* --stream-jpeg-subsampling: the viewer's JPEG chroma,
                                               4:2:0 by default as fluidcast view asks */
} e2e_options;

/* The defaults of e2e_options.c's table (16k,64k particles, 640x360,1280x720,
 * JPEG q90 and PNG, 20 requests, 10 s streams pushed as fast as accepted,
 * software GL); an error only for a default its setter refuses. */
fc_code e2e_options_default(e2e_options *o, fc_error *err);

/* Parses argv over the defaults; FC_ERR_USAGE naming the offending argument. */
fc_code e2e_options_parse(int argc, char **argv, e2e_options *o, fc_error *err);

void e2e_options_print_usage(void);

/* "png", "jpeg", ... for the tables. */
const char *e2e_format_name(fc_image_format f);

#endif
