/* test_srv_order.c — the placement contract of "srv:" addresses, without DNS:
 * the rendezvous score's pinned values (clients of every version must agree),
 * an even spread, the few names that move when a daemon is added or removed,
 * weights, priorities, and the RFC 2782 weighted order for session-less
 * connections. */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "srv_target.h"
#include "test_util.h"

enum { NAMES = 3000 };

static fc_srv_target target(const char *host, uint16_t port, uint16_t priority, uint16_t weight)
{
    fc_srv_target t;
    memset(&t, 0, sizeof t);
    snprintf(t.host, sizeof t.host, "%s", host);
    t.port = port;
    t.priority = priority;
    t.weight = weight;
    return t;
}

static void session_name(int i, char out[32])
{
    snprintf(out, 32, "sim-%d", i);
}

/* The host:port a session lands on among `targets` (copied: ordering sorts in place). */
static void place(const fc_srv_target *targets, size_t count, const char *session, fc_srv_target *first)
{
    fc_srv_target copy[FC_SRV_MAX_TARGETS];
    memcpy(copy, targets, count * sizeof copy[0]);
    fc_srv_order_for_session(copy, count, session);
    *first = copy[0];
}

static bool same_target(const fc_srv_target *a, const fc_srv_target *b)
{
    return strcmp(a->host, b->host) == 0 && a->port == b->port;
}

/* Computed independently from the formula in fluidcast.h (FNV-1a 64 of
 * "dam\0node-a.example:7450", fmix64): a change here breaks every deployment
 * whose clients run different versions. */
static void test_pinned_scores(void)
{
    CHECK(fc_srv_rendezvous_score("dam", "node-a.example", 7450) == 0x61ce8cb6723f293bull);
    CHECK(fc_srv_rendezvous_score("dam", "node-b.example", 7450) == 0x3d27b9513f91346cull);
    CHECK(fc_srv_rendezvous_score("", "a", 1) == 0x92e88ee1f3726f7full);
    /* the zero byte separates the name from the host: "a"+"bc" is not "ab"+"c" */
    CHECK(fc_srv_rendezvous_score("a", "bc", 1) != fc_srv_rendezvous_score("ab", "c", 1));
}

static void test_even_spread_and_order_independence(void)
{
    fc_srv_target three[3] = {target("a.fc", 7450, 0, 10), target("b.fc", 7450, 0, 10), target("c.fc", 7450, 0, 10)};
    fc_srv_target reversed[3] = {three[2], three[1], three[0]};
    int hits[3] = {0};
    for (int i = 0; i < NAMES; i++) {
        char name[32];
        session_name(i, name);
        fc_srv_target first, first_reversed;
        place(three, 3, name, &first);
        place(reversed, 3, name, &first_reversed);
        CHECK_MSG(same_target(&first, &first_reversed), "%s: placement depends on the order of the records", name);
        for (int k = 0; k < 3; k++)
            hits[k] += same_target(&first, &three[k]);
    }
    for (int k = 0; k < 3; k++)
        CHECK_MSG(hits[k] > NAMES * 0.28 && hits[k] < NAMES * 0.39, "target %d got %d of %d names", k, hits[k],
                  NAMES);
}

/* Adding a fourth daemon moves about a quarter of the names, all of them to it;
 * removing one moves only the names it had. */
static void test_minimal_disruption(void)
{
    fc_srv_target four[4] = {target("a.fc", 7450, 0, 10), target("b.fc", 7450, 0, 10), target("c.fc", 7450, 0, 10),
                             target("d.fc", 7451, 0, 10)};
    int moved = 0, removed_moved = 0;
    for (int i = 0; i < NAMES; i++) {
        char name[32];
        session_name(i, name);
        fc_srv_target before, after, without_b;
        place(four, 3, name, &before);
        place(four, 4, name, &after);
        if (!same_target(&before, &after)) {
            moved++;
            CHECK_MSG(same_target(&after, &four[3]), "%s moved to %s, not to the new daemon", name, after.host);
        }
        fc_srv_target ac[2] = {four[0], four[2]};
        place(ac, 2, name, &without_b);
        if (!same_target(&before, &without_b)) {
            removed_moved++;
            CHECK_MSG(same_target(&before, &four[1]), "%s moved off %s, which stayed", name, before.host);
        }
    }
    CHECK_MSG(moved > NAMES * 0.20 && moved < NAMES * 0.30, "%d of %d names moved to the 4th daemon", moved, NAMES);
    CHECK_MSG(removed_moved > NAMES * 0.28 && removed_moved < NAMES * 0.39, "%d of %d moved off the removed daemon",
              removed_moved, NAMES);
}

/* Within a priority a daemon's share follows its weight; a lower priority
 * value always wins, the higher one stays as the fallback order. */
static void test_weights_and_priorities(void)
{
    fc_srv_target weighted[2] = {target("big.fc", 7450, 0, 30), target("small.fc", 7450, 0, 10)};
    fc_srv_target tiers[3] = {target("backup.fc", 7450, 5, 100), target("x.fc", 7450, 0, 1),
                              target("y.fc", 7450, 0, 1)};
    int big = 0;
    for (int i = 0; i < NAMES; i++) {
        char name[32];
        session_name(i, name);
        fc_srv_target first;
        place(weighted, 2, name, &first);
        big += same_target(&first, &weighted[0]);
        fc_srv_target order[3];
        memcpy(order, tiers, sizeof order);
        fc_srv_order_for_session(order, 3, name);
        CHECK_MSG(order[0].priority == 0 && order[1].priority == 0 && strcmp(order[2].host, "backup.fc") == 0,
                  "%s: order %s %s %s ignores the priorities", name, order[0].host, order[1].host, order[2].host);
    }
    CHECK_MSG(big > NAMES * 0.70 && big < NAMES * 0.80, "weight 30 of 40 got %d of %d names", big, NAMES);
}

/* Without a session: random in proportion to the weights, priorities first. */
static void test_weighted_random_order(void)
{
    uint64_t state = 12345;
    int first_big = 0;
    for (int i = 0; i < NAMES; i++) {
        fc_srv_target order[3] = {target("big.fc", 1, 0, 60), target("small.fc", 2, 0, 20),
                                  target("later.fc", 3, 1, 1000)};
        uint64_t bits[3];
        for (int k = 0; k < 3; k++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            bits[k] = state;
        }
        fc_srv_order_weighted(order, 3, bits);
        first_big += order[0].port == 1;
        CHECK_MSG(order[2].port == 3, "the priority-1 target is tried before a priority-0 one");
    }
    CHECK_MSG(first_big > NAMES * 0.70 && first_big < NAMES * 0.80, "weight 60 of 80 was first %d of %d times",
              first_big, NAMES);
}

int main(void)
{
    test_pinned_scores();
    test_even_spread_and_order_independence();
    test_minimal_disruption();
    test_weights_and_priorities();
    test_weighted_random_order();
    return test_result();
}
