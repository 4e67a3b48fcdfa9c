/* main.c — the fluidcast command: dispatches to its subcommands. */
#include <stdio.h>
#include <string.h>

#include "cli_connect.h"
#include "cli_report.h"
#include "cli_token.h"
#include "info.h"
#include "mesh_command.h"
#include "render.h"
#include "snapshot.h"
#include "spacemouse_dump.h"
#include "stream.h"
#include "view_command.h"
#include "watch.h"
#include "wire.h"

static void print_help(FILE *to)
{
    fputs("usage: fluidcast COMMAND [options]\n"
          "       fluidcast --help | --version\n"
          "\n"
          "Client of the fluidcastd remote fluid renderer.\n"
          "\n"
          "commands:\n"
          "  snapshot INPUT -o OUT   render one particle file to an image\n"
          "                          (fluidcast snapshot --help for its options)\n"
          "  render INPUTS... -o OUT render a sequence of particle files to a video\n"
          "                          (.mp4, .webm) or numbered images\n"
          "  mesh INPUTS... -o OUT   the fluid's surface as triangle meshes (.ply, .obj,\n"
          "                          .vtp, .stl), extracted by the server\n"
          "  stream FILES...         push a sequence of particle files as frames, into a\n"
          "                          session (--session) and/or rendered back (--out-dir)\n"
          "  watch --session NAME    follow a session's frames as a viewer\n"
          "  view FILES... | --session NAME\n"
          "                          an interactive window: play a sequence or follow a\n"
          "                          session, camera on mouse and SpaceMouse\n"
          "  info                    the server's version, renderer, limits and sessions\n"
          "                          (fluidcast COMMAND --help for the options of each)\n"
          "  spacemouse --dump       print a SpaceMouse's reports (USB, no spacenavd)\n"
          "\n"
          "every command:\n"
          "  --token-file PATH       send the token in PATH (its first line) to a daemon\n"
          "                          that requires one; without it FLUIDCAST_TOKEN, if set\n"
          "  --connect-timeout S     wait at most S seconds to reach the server and for\n"
          "                          its answer to the handshake (default 10; without it\n"
          "                          FLUIDCAST_CONNECT_TIMEOUT, if set)\n",
          to);
    fc_cli_tls_print_help(to);
    fputc('\n', to);
    fc_cli_print_exit_codes(to);
}

int main(int argc, char **argv)
{
    fc_error err;
    if (fc_cli_token_take(&argc, argv, &err) != FC_OK)
        return fc_cli_fail(err.code == FC_ERR_USAGE ? FC_EXIT_USAGE : FC_EXIT_INPUT, "%s", err.message);
    if (fc_cli_connect_timeout_take(&argc, argv, &err) != FC_OK || fc_cli_tls_take(&argc, argv, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    if (argc < 2) {
        print_help(stderr);
        return FC_EXIT_USAGE;
    }
    const char *command = argv[1];
    if (strcmp(command, "--help") == 0 || strcmp(command, "-h") == 0) {
        print_help(stdout);
        return FC_EXIT_OK;
    }
    if (strcmp(command, "--version") == 0) {
        printf("fluidcast %s (protocol %u)\n", FLUIDCAST_VERSION, FC_PROTOCOL_VERSION);
        return FC_EXIT_OK;
    }
    if (strcmp(command, "snapshot") == 0)
        return fc_snapshot_main(argc - 2, argv + 2);
    if (strcmp(command, "render") == 0)
        return fc_render_main(argc - 2, argv + 2);
    if (strcmp(command, "mesh") == 0)
        return fc_mesh_main(argc - 2, argv + 2);
    if (strcmp(command, "stream") == 0)
        return fc_stream_main(argc - 2, argv + 2);
    if (strcmp(command, "watch") == 0)
        return fc_watch_main(argc - 2, argv + 2);
    if (strcmp(command, "view") == 0)
        return fc_view_command(argc - 2, argv + 2);
    if (strcmp(command, "info") == 0)
        return fc_info_main(argc - 2, argv + 2);
    if (strcmp(command, "spacemouse") == 0)
        return fc_spacemouse_main(argc - 2, argv + 2);
    return fc_cli_fail(FC_EXIT_USAGE, "unknown command \"%s\" (see fluidcast --help)", command);
}
