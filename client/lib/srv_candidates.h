/* srv_candidates.h — the daemons to try, in order, for an "srv:NAME" address. */
#ifndef FC_SRV_CANDIDATES_H
#define FC_SRV_CANDIDATES_H

#include <stdbool.h>

#include "srv_target.h"

/* True when address is "srv:NAME". */
bool fc_srv_is_address(const char *address);

/* Looks up the SRV records of the NAME in "srv:NAME" and orders them: by
 * rendezvous hashing of `session` when it is non-NULL and non-empty, by RFC 2782
 * priority and weighted random choice otherwise. targets gets up to
 * FC_SRV_MAX_TARGETS entries, *count says how many. Errors of fc_srv_lookup;
 * FC_ERR_USAGE for an empty NAME. */
fc_code fc_srv_candidates(const char *address, const char *session, fc_srv_target *targets, size_t *count,
                          fc_error *err);

/* "HOST:PORT" of a target into out (FC_HOST_MAX + 8 bytes; a host holding ':' is bracketed). */
void fc_srv_target_address(const fc_srv_target *target, char *out, size_t size);

#endif
