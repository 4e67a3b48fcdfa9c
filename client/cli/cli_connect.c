/* cli_connect.c — see cli_connect.h. */
#define _POSIX_C_SOURCE 200809L
#include "cli_connect.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "cli_token.h"
#include "fc_error.h"

static const char TIMEOUT_OPTION[] = "--connect-timeout";
static const char TIMEOUT_VARIABLE[] = "FLUIDCAST_CONNECT_TIMEOUT";
#define TIMEOUT_MAX_S 3600.0

/* Seconds in (0, TIMEOUT_MAX_S] as milliseconds (at least 1); 0 when `text` is none. */
static uint32_t timeout_ms(const char *text)
{
    char *end = NULL;
    errno = 0;
    double seconds = strtod(text, &end);
    if (errno != 0 || end == text || *end != '\0' || !(seconds > 0.0 && seconds <= TIMEOUT_MAX_S))
        return 0;
    uint32_t ms = (uint32_t)(seconds * 1000.0 + 0.5);
    return ms > 0 ? ms : 1;
}

static fc_code publish_timeout(const char *value, fc_error *err)
{
    if (timeout_ms(value) == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s %s: not a number of seconds in (0, %.0f]", TIMEOUT_OPTION,
                            value, TIMEOUT_MAX_S);
    if (setenv(TIMEOUT_VARIABLE, value, 1) != 0)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot set %s: %s", TIMEOUT_VARIABLE, strerror(errno));
    return FC_OK;
}

fc_code fc_cli_connect_timeout_take(int *argc, char **argv, fc_error *err)
{
    return fc_cli_take_global(argc, argv, TIMEOUT_OPTION, publish_timeout, err);
}

fc_connect_options fc_cli_connect_options(const char *client_name)
{
    const char *timeout = getenv(TIMEOUT_VARIABLE);
    return (fc_connect_options){.client_name = client_name,
                                .token = fc_cli_token(),
                                .connect_timeout_ms = timeout ? timeout_ms(timeout) : 0};
}

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
