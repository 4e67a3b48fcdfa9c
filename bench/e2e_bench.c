/* e2e_bench.c — fluidcast-e2e-bench: particle upload -> image at the client
 * over loopback, through a real fluidcastd (started here or given with
 * --server). Prints markdown tables; progress goes to stderr. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "daemon_process.h"
#include "e2e_options.h"
#include "e2e_request.h"
#include "e2e_stream.h"
#include "fc_error.h"
#include "fluidcast.h"

typedef struct run_plan {
    const e2e_options *options;
    char load_before[64];          /* sampled before the first request: the tables print at the end */
    char date[64];                 /* when it started */
    const char *address;
    e2e_config *configs;
    int n_configs;
} run_plan;

static e2e_config *make_configs(const e2e_options *o, int *count)
{
    *count = o->n_particles * o->n_sizes * o->n_formats;
    e2e_config *configs = calloc((size_t)*count, sizeof *configs);
    int n = 0;
    for (int p = 0; configs && p < o->n_particles; p++)
        for (int s = 0; s < o->n_sizes; s++)
            for (int f = 0; f < o->n_formats; f++)
                configs[n++] = (e2e_config){o->particles[p], o->sizes[s][0], o->sizes[s][1],
                                            {o->formats[f], o->quality, FC_AOV_COLOR}, o->density,
                                            o->stream_subsampling};
    return configs;
}

static void print_config_cells(const e2e_config *c)
{
    printf("| %llu | %ux%u | %s ", (unsigned long long)c->particles, c->width, c->height,
           e2e_format_name(c->request.format));
}

/* /proc/loadavg's three averages, or "unknown". */
static void read_load(char *out, size_t size)
{
    snprintf(out, size, "unknown");
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f)
        return;
    double a, b, c;
    if (fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3)
        snprintf(out, size, "%.2f %.2f %.2f (1, 5, 15 min)", a, b, c);
    fclose(f);
}

static void print_header(int argc, char **argv, const fc_server_info *info, const run_plan *plan)
{
    char host[256] = "?";
    gethostname(host, sizeof host - 1);
    printf("# fluidcast end-to-end loopback benchmark\n\n");
    printf("- machine: %s, %ld cores\n", host, sysconf(_SC_NPROCESSORS_ONLN));
    printf("- renderer: %s (%s at %s%s)\n", info->renderer, info->server_version, plan->address,
           plan->options->server ? "" : ", started by the benchmark");
    printf("- date: %s\n", plan->date);
    printf("- load average before: %s\n", plan->load_before);
    printf("- command: `");
    for (int i = 0; i < argc; i++)
        printf(i ? " %s" : "%s", argv[i]);
    printf("`\n");
}

static void print_request_tables(const run_plan *plan, const e2e_request_result *r)
{
    printf("\n## Request/response\n\nLatency: start of sending the frame until the image is fully received, after "
           "one untimed warm-up request per configuration. p99: nearest rank (the ceil(0.99 n)-th smallest, "
           "so the maximum for n <= 100). fps = 1000 / mean.\n\n");
    printf("| particles | size | format | requests | median ms | p99 ms | mean ms | fps | image KiB |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < plan->n_configs; i++) {
        print_config_cells(&plan->configs[i]);
        printf("| %d | %.2f | %.2f | %.2f | %.2f | %.1f |\n", r[i].answered, r[i].latency.median_ms,
               r[i].latency.p99_ms, r[i].latency.mean_ms,
               r[i].latency.mean_ms > 0 ? 1000.0 / r[i].latency.mean_ms : 0, r[i].image_kib);
    }
    static const struct { fc_stage stage; const char *name; } stages[] = {
        {FC_STAGE_RECEIVE, "receive"}, {FC_STAGE_DECODE, "decode"}, {FC_STAGE_QUEUE, "queue"},
        {FC_STAGE_UPLOAD, "upload"}, {FC_STAGE_DEPTH, "depth"}, {FC_STAGE_THICKNESS, "thickness"},
        {FC_STAGE_SMOOTHING, "smoothing"}, {FC_STAGE_COMPOSITE, "composite"}, {FC_STAGE_READBACK, "readback"},
        {FC_STAGE_ENCODE, "encode"}, {FC_STAGE_TOTAL, "server total"}};
    enum { N_STAGES = sizeof stages / sizeof stages[0] };
    printf("\n## Server stages per request\n\nMeans in ms of the times each IMAGE carries (protocol 7.7; "
           "\"server total\" runs from the RENDER's arrival to the reply being queued, so it excludes "
           "receive and decode of the frame; - = not measured).\n\n| particles | size | format |");
    for (int s = 0; s < N_STAGES; s++)
        printf(" %s |", stages[s].name);
    printf("\n|---|---|---|");
    for (int s = 0; s < N_STAGES; s++)
        printf("---|");
    printf("\n");
    for (int i = 0; i < plan->n_configs; i++) {
        print_config_cells(&plan->configs[i]);
        for (int s = 0; s < N_STAGES; s++) {
            double ms = r[i].stage_ms[stages[s].stage];
            ms >= 0 ? printf("| %.2f ", ms) : printf("| - ");
        }
        printf("|\n");
    }
}

static void print_stream_table(const run_plan *plan, const e2e_stream_result *r)
{
    const e2e_options *o = plan->options;
    printf("\n## Streaming\n\nA producer pushes frames for %g s (%s); a viewer on its own connection receives "
           "them. skipped: frames the server never rendered for the viewer (latest wins, the `missed` of "
           "its images); in flight: pushed - received - skipped after the session ended. viewer fps: "
           "received / (the last image or the end of pushing, the later, - first push). Latency: start of pushing a frame until its image is fully "
           "at the viewer; p99 as above.\n\n",
           o->stream_seconds, o->push_fps > 0 ? "at a fixed rate" : "as fast as the server accepts");
    printf("| particles | size | format | pushed | push fps | received | skipped | in flight | viewer fps | "
           "median ms | p99 ms |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < plan->n_configs; i++) {
        print_config_cells(&plan->configs[i]);
        printf("| %llu | %.1f | %llu | %llu | %lld | %.2f | %.2f | %.2f |\n", (unsigned long long)r[i].pushed,
               r[i].push_fps, (unsigned long long)r[i].received, (unsigned long long)r[i].skipped,
               (long long)r[i].in_flight, r[i].viewer_fps, r[i].latency.median_ms, r[i].latency.p99_ms);
    }
}

static fc_code run_requests(const run_plan *plan, fc_client *client, e2e_request_result *results, fc_error *err)
{
    for (int i = 0; i < plan->n_configs; i++) {
        const e2e_config *c = &plan->configs[i];
        fprintf(stderr, "requests: %llu particles, %ux%u %s\n", (unsigned long long)c->particles, c->width,
                c->height, e2e_format_name(c->request.format));
        fc_code code = e2e_run_requests(client, c, plan->options->requests, &results[i], err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

static fc_code run_streams(const run_plan *plan, e2e_stream_result *results, fc_error *err)
{
    for (int i = 0; i < plan->n_configs; i++) {
        const e2e_config *c = &plan->configs[i];
        char session[64];
        snprintf(session, sizeof session, "e2e-bench-%ld-%d", (long)getpid(), i);
        fprintf(stderr, "stream: %llu particles, %ux%u %s\n", (unsigned long long)c->particles, c->width,
                c->height, e2e_format_name(c->request.format));
        e2e_stream_plan sp = {plan->address, session, plan->options->stream_seconds, plan->options->push_fps};
        fc_code code = e2e_run_stream(&sp, c, &results[i], err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

static fc_code run_all(int argc, char **argv, run_plan *plan, fc_error *err)
{
    read_load(plan->load_before, sizeof plan->load_before);
    time_t now = time(NULL);
    struct tm utc;
    snprintf(plan->date, sizeof plan->date, "?");
    if (gmtime_r(&now, &utc))
        strftime(plan->date, sizeof plan->date, "%Y-%m-%d %H:%M UTC", &utc);
    fc_connect_options options = {.client_name = "e2e-bench"};
    fc_client *client;
    fc_code code = fc_client_connect(plan->address, &options, &client, err);
    if (code != FC_OK)
        return code;
    fc_server_info info;
    fc_client_server_info(client, &info);
    e2e_request_result *requests = calloc((size_t)plan->n_configs, sizeof *requests);
    e2e_stream_result *streams = calloc((size_t)plan->n_configs, sizeof *streams);
    if (!requests || !streams)
        code = fc_error_set(err, FC_ERR_NOMEM, "no memory for %d results", plan->n_configs);
    if (code == FC_OK && plan->options->requests > 0)
        code = run_requests(plan, client, requests, err);
    if (code == FC_OK && plan->options->stream_seconds > 0)
        code = run_streams(plan, streams, err);
    fc_client_close(client);
    if (code == FC_OK) {
        print_header(argc, argv, &info, plan);
        if (plan->options->requests > 0)
            print_request_tables(plan, requests);
        if (plan->options->stream_seconds > 0)
            print_stream_table(plan, streams);
        char load_after[64];
        read_load(load_after, sizeof load_after);
        printf("\n- load average after: %s\n", load_after);
    }
    free(requests);
    free(streams);
    return code;
}

/* Starts the daemon unless --server names one, runs, stops it. */
static fc_code run_with_daemon(int argc, char **argv, run_plan *plan, fc_error *err)
{
    const e2e_options *o = plan->options;
    if (o->server) {
        plan->address = o->server;
        return run_all(argc, argv, plan, err);
    }
    /* Warnings only: its per-connection info lines would bury the benchmark's progress. */
    const char *const args[] = {"--gpu", o->gpu, "--log-level", "warn", NULL};
    fc_test_daemon_setup setup = {.daemon_path = o->daemon_path, .extra_args = args};
    fc_test_daemon daemon;
    fc_code code = fc_test_daemon_start_with(&daemon, &setup, FC_TEST_DAEMON_START_TIMEOUT_MS, err);
    if (code != FC_OK)
        return code;
    char address[32];
    snprintf(address, sizeof address, "127.0.0.1:%u", (unsigned)daemon.port);
    plan->address = address;
    code = run_all(argc, argv, plan, err);
    fc_error stop_err;
    fc_code stopped = fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &stop_err);
    if (code == FC_OK && stopped != FC_OK) {
        *err = stop_err;
        code = stopped;
    }
    return code;
}

int main(int argc, char **argv)
{
    e2e_options options;
    fc_error err = {0};
    if (e2e_options_default(&options, &err) != FC_OK || e2e_options_parse(argc, argv, &options, &err) != FC_OK) {
        fprintf(stderr, "fluidcast-e2e-bench: %s\n", err.message);
        return 2;
    }
    if (options.help) {
        e2e_options_print_usage();
        return 0;
    }
    run_plan plan = {.options = &options};
    plan.configs = make_configs(&options, &plan.n_configs);
    if (!plan.configs) {
        fprintf(stderr, "fluidcast-e2e-bench: out of memory\n");
        return 1;
    }
    fc_code code = run_with_daemon(argc, argv, &plan, &err);
    free(plan.configs);
    if (code != FC_OK) {
        fprintf(stderr, "fluidcast-e2e-bench: %s\n", err.message);
        return 1;
    }
    return 0;
}
