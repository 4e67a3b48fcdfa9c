/* monotonic.h — milliseconds on the monotonic clock, for stage timings and deadlines. */
#ifndef FC_DAEMON_MONOTONIC_H
#define FC_DAEMON_MONOTONIC_H

#include <time.h>

static inline double fc_monotonic_ms(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec * 1e3 + (double)now.tv_nsec / 1e6;
}

#endif
