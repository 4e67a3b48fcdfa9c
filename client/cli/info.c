/* info.c — `fluidcast info`: the server's version, renderer, limits and
 * capabilities from its WELCOME, and its live sessions. */
#include "info.h"

#include <stdbool.h>
#include <stdio.h>

#include "cli_connect.h"
#include "cli_args.h"
#include "cli_report.h"
#include "fc_error.h"
#include "fluidcast.h"

#include "fc_host_port.h"

typedef struct info_options {
    const char *server;
} info_options;

static fc_code set_server(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((info_options *)o)->server = value;
    return FC_OK;
}

static const fc_cli_option options[] = {{"--server", true, set_server}};
static const fc_cli_command command = {"info", options, 1, NULL, NULL};

static void print_help(FILE *to)
{
    fputs("usage: fluidcast info [--server ADDR]\n"
          "\n"
          "Prints what a fluidcastd server announces (version, protocol, GL renderer,\n"
          "limits, capabilities) and its sessions with their producers, viewers and frames.\n"
          "\n"
          "options:\n"
          "  --server ADDR           HOST:PORT or unix:PATH (default " FC_DEFAULT_SERVER ")\n"
          "                          or srv:NAME, a DNS SRV name: one of its daemons by\n"
          "                          SRV priority and weight\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}

static void print_server(const fc_server_info *s)
{
    printf("server:       %s (protocol %u)\n", s->server_version, (unsigned)s->protocol_version);
    printf("renderer:     %s\n", s->renderer);
    printf("device:       %s\n", s->device[0] ? s->device : "(not reported by this server)");
    printf("limits:       %llu particles per frame, %ux%u pixels, %u-byte messages\n",
           (unsigned long long)s->max_particles, (unsigned)s->max_width, (unsigned)s->max_height,
           (unsigned)s->max_message);
    printf("capabilities:%s%s%s%s%s\n", s->capabilities & FC_SERVER_CAN_STREAM ? " sessions" : "",
           s->capabilities & FC_SERVER_CAN_ZSTD ? " zstd" : "",
           s->capabilities & FC_SERVER_CAN_QUANTIZE16 ? " quantize16" : "",
           s->capabilities & FC_SERVER_CAN_DEVICE ? " device" : "", s->capabilities ? "" : " none");
}

static void print_sessions(const fc_session_status *list, uint32_t count)
{
    printf("sessions:     %u\n", (unsigned)count);
    for (uint32_t i = 0; i < count; i++)
        printf("  %s: %u producer(s), %u viewer(s), %llu frame(s), latest frame %llu\n", list[i].name,
               (unsigned)list[i].producers, (unsigned)list[i].viewers, (unsigned long long)list[i].frames,
               (unsigned long long)list[i].last_frame);
}

static int info(const info_options *o)
{
    fc_connect_options connect_options = fc_cli_connect_options("fluidcast info");
    fc_client *c;
    fc_error err;
    if (fc_cli_connect(o->server, NULL, &connect_options, &c, &err) != FC_OK)
        return fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s", err.message);
    fc_server_info server;
    fc_client_server_info(c, &server);
    print_server(&server);
    int status = FC_EXIT_OK;
    if (server.capabilities & FC_SERVER_CAN_STREAM) {
        fc_session_status *list;
        uint32_t count;
        if (fc_client_list_sessions(c, &list, &count, &err) == FC_OK) {
            print_sessions(list, count);
            fc_session_list_free(list);
        } else {
            status = fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s: %s", o->server, err.message);
        }
    }
    fc_client_close(c);
    return status;
}

int fc_info_main(int argc, char **argv)
{
    info_options options = {FC_DEFAULT_SERVER};
    bool help;
    fc_error err;
    if (fc_cli_parse_args(&command, argc, argv, &options, &help, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    if (help) {
        print_help(stdout);
        return FC_EXIT_OK;
    }
    return info(&options);
}
