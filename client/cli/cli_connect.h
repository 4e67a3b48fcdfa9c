/* cli_connect.h — how every fluidcast command connects: the library's connect,
 * placed by the session name for "srv:" addresses, saying which daemon it chose. */
#ifndef FC_CLI_CONNECT_H
#define FC_CLI_CONNECT_H

#include <stdio.h>

#include "fluidcast.h"

/* Removes "--connect-timeout SECONDS" (or "=SECONDS") from argv, wherever it
 * stands, and publishes it as FLUIDCAST_CONNECT_TIMEOUT: how long every
 * command waits to reach the server and for its WELCOME (default 10 s; a
 * socket-activated fluidcastd on llvmpipe with no shader cache takes about
 * 6 s to answer). FC_ERR_USAGE for a value that is not a number of seconds
 * in (0, 3600]. */
fc_code fc_cli_connect_timeout_take(int *argc, char **argv, fc_error *err);

/* Removes the TLS options (--tls, --tls-ca FILE, --tls-cert FILE, --tls-key
 * FILE) from argv, wherever they stand, and publishes them as the environment
 * variables FLUIDCAST_TLS, FLUIDCAST_TLS_CA, FLUIDCAST_TLS_CERT and
 * FLUIDCAST_TLS_KEY, which set them as well. FC_ERR_USAGE for a missing value. */
fc_code fc_cli_tls_take(int *argc, char **argv, fc_error *err);

/* The lines of the TLS options for a help text. */
void fc_cli_tls_print_help(FILE *to);

/* The options every command connects with: its name, the token
 * (cli_token.h), the connect timeout (FLUIDCAST_CONNECT_TIMEOUT, which an
 * invalid value leaves at the library's default) and TLS (fc_cli_tls_take). */
fc_connect_options fc_cli_connect_options(const char *client_name);

/* fc_client_connect_session(server, session, ...). For an "srv:NAME" server a
 * line on stderr names the daemon chosen ("fluidcast: srv:NAME -> HOST:PORT"
 * and the session), so an operator sees where a session lives. */
fc_code fc_cli_connect(const char *server, const char *session, const fc_connect_options *options,
                       fc_client **out, fc_error *err);

#endif
