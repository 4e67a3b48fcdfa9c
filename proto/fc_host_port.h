/* fc_host_port.h — the one grammar of a TCP address, "HOST:PORT", shared by the
 * clients' --server / fc_client_connect and the daemon's --listen and
 * --metrics-listen (proto/PROTOCOL.md section 1.1 is its description).
 *
 *   host:port      a name or IPv4 address and a port
 *   [v6]:port      an IPv6 address, always in brackets
 *   host, [v6]     the caller's default port (an error when it has none)
 *
 * A bare IPv6 literal ("::1", "fe80::1:7450") is refused with an error that
 * asks for brackets: without them "::1:7450" could be the address ::1:7450 or
 * ::1 at port 7450, and neither reading is obviously the one meant.
 * "unix:PATH" and "srv:NAME" are recognised by their prefix before this
 * grammar is used (client/lib, server/daemon). */
#ifndef FC_HOST_PORT_H
#define FC_HOST_PORT_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"   /* FC_DEFAULT_PORT, FC_DEFAULT_HOST, FC_DEFAULT_SERVER */

#define FC_HOST_MAX 256   /* bytes of a host, NUL included (DNS names are at most 253) */
#define FC_PORT_MAX 6     /* "65535" + NUL */

/* How one use of the grammar differs from another. */
typedef struct fc_host_port_rules {
    const char *what;          /* names the text in errors: "server address", "--listen" */
    uint16_t default_port;     /* for "host" and "[v6]"; 0: a port is required */
    bool port_zero;            /* port 0 ("any free port") allowed: for listening */
} fc_host_port_rules;

/* The rules of a client's server address: port 1..65535, FC_DEFAULT_PORT when none. */
extern const fc_host_port_rules fc_server_address_rules;

/* Splits text into host (brackets removed) and port (decimal, leading zeros
 * dropped). FC_ERR_USAGE "WHAT \"TEXT\": PROBLEM" otherwise. */
fc_code fc_host_port_parse(const char *text, const fc_host_port_rules *rules, char host[FC_HOST_MAX],
                           char port[FC_PORT_MAX], fc_error *err);

#endif
