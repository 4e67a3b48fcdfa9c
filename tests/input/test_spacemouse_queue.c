/* test_spacemouse_queue.c — the event queue between the libusb thread and its
 * user: order, a full queue drops the oldest and says how many, waits time
 * out, and a producer thread's events reach a waiting consumer. */
#include <pthread.h>
#include <string.h>
#include <time.h>

#include "spacemouse_events.h"
#include "test_util.h"

static fc_sm_event report(size_t n)
{
    fc_sm_event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = FC_SM_EVENT_REPORT;
    ev.length = n;
    return ev;
}

static void test_order_and_overflow(void)
{
    fc_sm_queue *q;
    fc_error err;
    CHECK_CODE(fc_sm_queue_create(0, &q, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_sm_queue_create(3, &q, &err), FC_OK);
    for (size_t i = 1; i <= 5; i++) {
        fc_sm_event ev = report(i);
        fc_sm_queue_push(q, &ev);
    }
    fc_sm_event ev;
    CHECK(fc_sm_queue_pop(q, &ev, 0) && ev.length == 3 && ev.dropped == 2);   /* 1 and 2 dropped */
    CHECK(fc_sm_queue_pop(q, &ev, 0) && ev.length == 4 && ev.dropped == 0);
    CHECK(fc_sm_queue_pop(q, &ev, 0) && ev.length == 5);
    CHECK(!fc_sm_queue_pop(q, &ev, 0));
    fc_sm_queue_destroy(q);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void *produce(void *arg)
{
    struct timespec pause = {0, 50 * 1000000L};
    nanosleep(&pause, NULL);
    fc_sm_event ev = report(42);
    fc_sm_queue_push(arg, &ev);
    return NULL;
}

static void test_waits(void)
{
    fc_sm_queue *q;
    fc_error err;
    CHECK_CODE(fc_sm_queue_create(4, &q, &err), FC_OK);
    fc_sm_event ev;
    double t0 = now_s();
    CHECK(!fc_sm_queue_pop(q, &ev, 100));
    double waited = now_s() - t0;
    CHECK_MSG(waited >= 0.09, "waited %.3f s for 100 ms", waited);   /* returning at all shows it ends */
    pthread_t thread;
    pthread_create(&thread, NULL, produce, q);
    CHECK(fc_sm_queue_pop(q, &ev, -1) && ev.length == 42);   /* wakes on the push */
    pthread_join(thread, NULL);
    fc_sm_queue_destroy(q);
}

int main(void)
{
    test_order_and_overflow();
    test_waits();
    return test_result();
}
