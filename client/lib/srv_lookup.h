/* srv_lookup.h — asking DNS for the SRV records of a name, with libresolv. */
#ifndef FC_SRV_LOOKUP_H
#define FC_SRV_LOOKUP_H

#include "srv_target.h"

/* The environment variable that points the SRV query at one DNS server,
 * "ADDR" or "ADDR:PORT" (IPv4, port 53 by default), instead of the servers of
 * /etc/resolv.conf: for tests and labs that run their own DNS server. Only the
 * SRV query uses it; the targets' addresses come from the system resolver. */
#define FC_DNS_SERVER_ENV "FLUIDCAST_DNS_SERVER"

/* Queries the SRV records of `name` (class IN) and fills targets with up to
 * `max` of them; *count says how many. FC_ERR_CONNECT naming the name when the
 * query fails (no such name, no SRV records, no answer, a server failure) or
 * the only record is the "." target (RFC 2782: the service is not offered
 * there); FC_ERR_USAGE for a malformed FLUIDCAST_DNS_SERVER; FC_ERR_PROTOCOL
 * for an answer libresolv cannot parse. */
fc_code fc_srv_lookup(const char *name, fc_srv_target *targets, size_t max, size_t *count, fc_error *err);

#endif
