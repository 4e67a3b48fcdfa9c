/* cli_connect.h — how every fluidcast command connects: the library's connect,
 * placed by the session name for "srv:" addresses, saying which daemon it chose. */
#ifndef FC_CLI_CONNECT_H
#define FC_CLI_CONNECT_H

#include "fluidcast.h"

/* fc_client_connect_session(server, session, ...). For an "srv:NAME" server a
 * line on stderr names the daemon chosen ("fluidcast: srv:NAME -> HOST:PORT"
 * and the session), so an operator sees where a session lives. */
fc_code fc_cli_connect(const char *server, const char *session, const fc_connect_options *options,
                       fc_client **out, fc_error *err);

#endif
