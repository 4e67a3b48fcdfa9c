/* srv_target.h — the daemons a DNS SRV name lists ("srv:_fluidcast._tcp.NAME"),
 * and the order a client tries them in: by rendezvous hashing of a session
 * name, so that every client of one session picks the same daemon, or by
 * RFC 2782 priority and weight when there is no session. */
#ifndef FC_SRV_TARGET_H
#define FC_SRV_TARGET_H

#include <stddef.h>
#include <stdint.h>
#include "fc_host_port.h"

#define FC_SRV_PREFIX "srv:"
#define FC_SRV_MAX_TARGETS 64   /* targets kept of one answer; a 64 KiB DNS message holds a few hundred */

typedef struct fc_srv_target {
    char host[FC_HOST_MAX];     /* the SRV target, without the trailing dot */
    uint16_t port;
    uint16_t priority;          /* lower is tried first */
    uint16_t weight;            /* share within one priority */
} fc_srv_target;

/* The rendezvous score of a session on a target: FNV-1a 64 over the bytes of
 * session, one zero byte, host, ':' and the port in decimal, then MurmurHash3's
 * 64-bit finaliser (FNV alone leaves similar inputs with similar high bits).
 * Part of the placement contract: clients of different versions must agree. */
uint64_t fc_srv_rendezvous_score(const char *session, const char *host, uint16_t port);

/* Orders targets for `session`: lowest priority first; within a priority by
 * decreasing weighted rendezvous key weight / -ln(u), u the score mapped into
 * (0, 1) (equal weights: simply by decreasing score), weight 0 counting as 0.01;
 * ties by host, then port. targets[0] is the session's daemon, the rest the
 * order to fall back in when it cannot be reached. */
void fc_srv_order_for_session(fc_srv_target *targets, size_t count, const char *session);

/* Orders targets as RFC 2782 says for one connection without a session: lowest
 * priority first; within a priority a weighted random order, drawn with
 * `random_bits` (any 64-bit values, one per target). */
void fc_srv_order_weighted(fc_srv_target *targets, size_t count, const uint64_t *random_bits);

#endif
