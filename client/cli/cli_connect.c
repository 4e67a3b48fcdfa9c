/* cli_connect.c — see cli_connect.h. */
#include "cli_connect.h"

#include <stdio.h>
#include <string.h>

fc_code fc_cli_connect(const char *server, const char *session, const fc_connect_options *options,
                       fc_client **out, fc_error *err)
{
    fc_code code = fc_client_connect_session(server, session, options, out, err);
    if (code == FC_OK && server && strncmp(server, "srv:", 4) == 0) {
        if (session)
            fprintf(stderr, "fluidcast: %s -> %s (session %s)\n", server, fc_client_address(*out), session);
        else
            fprintf(stderr, "fluidcast: %s -> %s\n", server, fc_client_address(*out));
    }
    return code;
}
