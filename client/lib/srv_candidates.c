/* srv_candidates.c — see srv_candidates.h. */
#include "srv_candidates.h"

#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/random.h>
#include <time.h>

#include "fc_error.h"
#include "srv_lookup.h"

bool fc_srv_is_address(const char *address)
{
    return address && strncmp(address, FC_SRV_PREFIX, strlen(FC_SRV_PREFIX)) == 0;
}

/* Random bits for the weighted choice. The kernel's generator; should it fail
 * (very old kernels), a clock-seeded mix still spreads connections. */
static void random_bits(uint64_t *bits, size_t count)
{
    size_t bytes = count * sizeof bits[0];
    if (getrandom(bits, bytes, GRND_NONBLOCK) == (ssize_t)bytes)
        return;
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    uint64_t x = (uint64_t)now.tv_nsec ^ ((uint64_t)now.tv_sec << 32);
    for (size_t i = 0; i < count; i++) {
        x += 0x9e3779b97f4a7c15ull;   /* splitmix64 */
        uint64_t z = x;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        bits[i] = z ^ (z >> 31);
    }
}

fc_code fc_srv_candidates(const char *address, const char *session, fc_srv_target *targets, size_t *count,
                          fc_error *err)
{
    *count = 0;
    const char *name = address + strlen(FC_SRV_PREFIX);
    if (*name == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" names no SRV record (srv:_fluidcast._tcp.NAME)",
                            address);
    fc_code code = fc_srv_lookup(name, targets, FC_SRV_MAX_TARGETS, count, err);
    if (code != FC_OK)
        return code;
    if (session && *session) {
        fc_srv_order_for_session(targets, *count, session);
    } else {
        uint64_t bits[FC_SRV_MAX_TARGETS];
        random_bits(bits, *count);
        fc_srv_order_weighted(targets, *count, bits);
    }
    return FC_OK;
}

void fc_srv_target_address(const fc_srv_target *target, char *out, size_t size)
{
    bool literal_v6 = strchr(target->host, ':') != NULL;
    snprintf(out, size, literal_v6 ? "[%s]:%u" : "%s:%u", target->host, (unsigned)target->port);
}
