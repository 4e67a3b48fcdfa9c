/* fuzz_srv_answer.c — libFuzzer target for fc_srv_parse_answer, the client's
 * reader of a DNS server's SRV answer ("srv:" addresses): the input is one DNS
 * message. libresolv parses it; the target checks what is made of it.
 *
 * Checked beyond memory safety: a refusal is FC_ERR_PROTOCOL or FC_ERR_CONNECT
 * with a reason; accepted targets number 1..max, each a terminated name that
 * is neither empty nor "."; ordering them for a session and by weight keeps the
 * same targets (a permutation), lowest priority first, and the session order is
 * the same whatever order the records came in. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_check.h"
#include "srv_answer.h"

enum { MAX = 8 };   /* small, so answers with more records exercise the cap */

static int compare_targets(const void *a, const void *b)
{
    const fc_srv_target *x = a, *y = b;
    int by_host = strcmp(x->host, y->host);
    if (by_host)
        return by_host;
    if (x->port != y->port)
        return x->port < y->port ? -1 : 1;
    if (x->priority != y->priority)
        return x->priority < y->priority ? -1 : 1;
    return (x->weight > y->weight) - (x->weight < y->weight);
}

static void require_permutation(const fc_srv_target *original, const fc_srv_target *ordered, size_t count)
{
    fc_srv_target a[MAX], b[MAX];
    memcpy(a, original, count * sizeof a[0]);
    memcpy(b, ordered, count * sizeof b[0]);
    qsort(a, count, sizeof a[0], compare_targets);
    qsort(b, count, sizeof b[0], compare_targets);
    for (size_t i = 0; i < count; i++)
        FUZZ_REQUIRE(compare_targets(&a[i], &b[i]) == 0, "ordering lost or changed target %zu", i);
    for (size_t i = 1; i < count; i++)
        FUZZ_REQUIRE(ordered[i - 1].priority <= ordered[i].priority, "priority %u before %u",
                     (unsigned)ordered[i - 1].priority, (unsigned)ordered[i].priority);
}

static void check_orders(const fc_srv_target *targets, size_t count)
{
    fc_srv_target by_session[MAX], reversed[MAX], weighted[MAX];
    memcpy(by_session, targets, count * sizeof targets[0]);
    for (size_t i = 0; i < count; i++)
        reversed[i] = targets[count - 1 - i];
    fc_srv_order_for_session(by_session, count, "fuzz");
    fc_srv_order_for_session(reversed, count, "fuzz");
    require_permutation(targets, by_session, count);
    FUZZ_REQUIRE(strcmp(by_session[0].host, reversed[0].host) == 0 && by_session[0].port == reversed[0].port,
                 "the session's daemon depends on the order of the records");
    uint64_t bits[MAX];
    for (size_t i = 0; i < count; i++)
        bits[i] = 0x9e3779b97f4a7c15ull * (i + 1);
    memcpy(weighted, targets, count * sizeof targets[0]);
    fc_srv_order_weighted(weighted, count, bits);
    require_permutation(targets, weighted, count);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 65535)
        return 0;
    /* An exact-size heap copy: any read past the message is a sanitizer report. */
    unsigned char *copy = malloc(size ? size : 1);
    if (!copy)
        return 0;
    memcpy(copy, data, size);
    fc_srv_target targets[MAX];
    size_t count = 99;
    fc_error err = {FC_OK, ""};
    fc_code code = fc_srv_parse_answer(copy, (int)size, "_fluidcast._tcp.fuzz", targets, MAX, &count, &err);
    if (code != FC_OK) {
        fuzz_require_reported(code, &err);
        FUZZ_REQUIRE(code == FC_ERR_PROTOCOL || code == FC_ERR_CONNECT, "unexpected code %d", (int)code);
    } else {
        FUZZ_REQUIRE(count >= 1 && count <= MAX, "%zu targets", count);
        for (size_t i = 0; i < count; i++) {
            FUZZ_REQUIRE(memchr(targets[i].host, '\0', sizeof targets[i].host) != NULL, "host not terminated");
            FUZZ_REQUIRE(targets[i].host[0] != '\0' && strcmp(targets[i].host, ".") != 0, "the \".\" target kept");
        }
        check_orders(targets, count);
    }
    free(copy);
    return 0;
}
