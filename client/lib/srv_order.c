/* srv_order.c — see srv_target.h. Pure functions: no DNS, no sockets, so the
 * placement contract is unit-tested on its own (tests/srv). */
#include "srv_target.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FNV64_OFFSET 0xcbf29ce484222325ull
#define FNV64_PRIME 0x100000001b3ull

static uint64_t fnv1a(uint64_t hash, const void *data, size_t size)
{
    const unsigned char *bytes = data;
    for (size_t i = 0; i < size; i++) {
        hash ^= bytes[i];
        hash *= FNV64_PRIME;
    }
    return hash;
}

/* MurmurHash3's fmix64: every input bit affects every output bit. */
static uint64_t mix64(uint64_t h)
{
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

uint64_t fc_srv_rendezvous_score(const char *session, const char *host, uint16_t port)
{
    char port_text[8];
    int port_len = snprintf(port_text, sizeof port_text, ":%u", (unsigned)port);
    uint64_t h = fnv1a(FNV64_OFFSET, session, strlen(session) + 1);   /* the NUL separates name and host */
    h = fnv1a(h, host, strlen(host));
    h = fnv1a(h, port_text, (size_t)port_len);
    return mix64(h);
}

/* 53 high bits into (0, 1): never 0 or 1, so -ln(u) is finite and positive. */
static double unit_interval(uint64_t bits)
{
    return ((double)(bits >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double effective_weight(uint16_t weight)
{
    return weight ? (double)weight : 0.01;
}

/* Highest-random-weight key: with equal weights its order is the order of the
 * scores (the logarithm is monotonic); with unequal ones a target wins a share
 * of the names proportional to its weight. */
static double weighted_key(uint64_t bits, uint16_t weight)
{
    return effective_weight(weight) / -log(unit_interval(bits));
}

typedef struct keyed_target {
    fc_srv_target target;
    double key;
} keyed_target;

static int compare_keyed(const void *a, const void *b)
{
    const keyed_target *x = a, *y = b;
    if (x->target.priority != y->target.priority)
        return x->target.priority < y->target.priority ? -1 : 1;
    if (x->key != y->key)
        return x->key > y->key ? -1 : 1;
    int by_host = strcmp(x->target.host, y->target.host);
    if (by_host != 0)
        return by_host;
    return (x->target.port > y->target.port) - (x->target.port < y->target.port);
}

static void sort_by_keys(fc_srv_target *targets, size_t count, const uint64_t *bits)
{
    keyed_target keyed[FC_SRV_MAX_TARGETS];
    if (count > FC_SRV_MAX_TARGETS)
        count = FC_SRV_MAX_TARGETS;
    for (size_t i = 0; i < count; i++) {
        keyed[i].target = targets[i];
        keyed[i].key = weighted_key(bits[i], targets[i].weight);
    }
    qsort(keyed, count, sizeof keyed[0], compare_keyed);
    for (size_t i = 0; i < count; i++)
        targets[i] = keyed[i].target;
}

void fc_srv_order_for_session(fc_srv_target *targets, size_t count, const char *session)
{
    uint64_t scores[FC_SRV_MAX_TARGETS];
    if (count > FC_SRV_MAX_TARGETS)
        count = FC_SRV_MAX_TARGETS;
    for (size_t i = 0; i < count; i++)
        scores[i] = fc_srv_rendezvous_score(session, targets[i].host, targets[i].port);
    sort_by_keys(targets, count, scores);
}

/* Ordering by weight / -ln(u) with independent uniform u is weighted random
 * sampling without replacement (Efraimidis-Spirakis), which is what RFC 2782's
 * running-sum selection repeated over the remaining targets amounts to. */
void fc_srv_order_weighted(fc_srv_target *targets, size_t count, const uint64_t *random_bits)
{
    sort_by_keys(targets, count, random_bits);
}
