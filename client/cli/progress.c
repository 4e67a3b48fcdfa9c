/* progress.c — see progress.h. */
#include "progress.h"

#include <time.h>

enum { BAR_WIDTH = 24 };

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

static double elapsed_s(const fc_progress *p)
{
    double s = (now_ms() - p->start_ms) / 1e3;
    return s > 1e-6 ? s : 1e-6;
}

static double saved_percent(const fc_progress *p)
{
    if (p->raw_bytes == 0)
        return 0.0;
    return 100.0 * (1.0 - (double)p->wire_bytes / (double)p->raw_bytes);
}

void fc_progress_start(fc_progress *p, FILE *to, bool tty, uint32_t total)
{
    *p = (fc_progress){.to = to, .tty = tty, .total = total, .start_ms = now_ms()};
}

/* Seconds the remaining frames take at the rate so far. */
static double seconds_left(const fc_progress *p)
{
    return p->done && p->total > p->done ? elapsed_s(p) * (p->total - p->done) / p->done : 0.0;
}

static void draw_bar(const fc_progress *p)
{
    char bar[BAR_WIDTH + 1];
    int filled = p->total ? (int)((uint64_t)p->done * BAR_WIDTH / p->total) : BAR_WIDTH;
    for (int i = 0; i < BAR_WIDTH; i++)
        bar[i] = i < filled ? '#' : '.';
    bar[BAR_WIDTH] = '\0';
    double s = elapsed_s(p);
    /* \r and erase-to-end-of-line redraw the bar in place. */
    fprintf(p->to, "\r%u/%u frames [%s] %.2f MB/s %.1f fps %.0f s left %.0f%% saved\033[K", p->done, p->total, bar,
            (double)p->wire_bytes / 1e6 / s, p->done / s, seconds_left(p), saved_percent(p));
    fflush(p->to);
}

void fc_progress_frame(fc_progress *p, const char *file, uint64_t particles, const fc_upload_stats *stats)
{
    p->done++;
    p->wire_bytes += stats->wire_bytes;
    p->raw_bytes += stats->raw_bytes;
    if (p->tty) {
        draw_bar(p);
        return;
    }
    fprintf(p->to, "frame %u/%u %s: %llu particles, %llu bytes sent (%llu raw), %.1f fps, %.0f s left\n", p->done,
            p->total, file, (unsigned long long)particles, (unsigned long long)stats->wire_bytes,
            (unsigned long long)stats->raw_bytes, p->done / elapsed_s(p), seconds_left(p));
    fflush(p->to);
}

void fc_progress_finish(fc_progress *p)
{
    if (p->tty)
        fputc('\n', p->to);
    double s = elapsed_s(p);
    fprintf(p->to, "streamed %u frames in %.2f s: %.1f fps, %.2f MB/s; %llu bytes sent for %llu raw (%.0f%% saved)\n",
            p->done, s, p->done / s, (double)p->wire_bytes / 1e6 / s, (unsigned long long)p->wire_bytes,
            (unsigned long long)p->raw_bytes, saved_percent(p));
    fflush(p->to);
}
