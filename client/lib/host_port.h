/* host_port.h — splitting a "HOST:PORT" server address into its parts. */
#ifndef FC_HOST_PORT_H
#define FC_HOST_PORT_H

#include <stddef.h>
#include "fluidcast_types.h"

#define FC_HOST_MAX 256   /* bytes of a host name, NUL included (DNS names are at most 253) */
#define FC_PORT_MAX 6     /* "65535" + NUL */

/* Accepts "HOST:PORT", "HOST", "[IPV6]:PORT", "[IPV6]" and a bare IPv6 literal
 * (more than one colon, no brackets). A missing port becomes FC_DEFAULT_PORT.
 * The port must be a decimal number in 1..65535. FC_ERR_USAGE naming the address
 * otherwise. host gets FC_HOST_MAX bytes, port FC_PORT_MAX. */
fc_code fc_host_port_parse(const char *text, char host[FC_HOST_MAX], char port[FC_PORT_MAX],
                           fc_error *err);

#endif
