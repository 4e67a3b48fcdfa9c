/* progress.h — what `fluidcast stream` and `render` tell while they push a
 * sequence: on a terminal one progress bar redrawn in place (frames, MB/s,
 * fps, time left, bytes saved),
 * otherwise one plain line per frame, for logs; a summary line at the end. */
#ifndef FC_PROGRESS_H
#define FC_PROGRESS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "fluidcast.h"

typedef struct fc_progress {
    FILE *to;
    bool tty;
    uint32_t total;          /* frames in the sequence */
    uint32_t done;
    double start_ms;
    uint64_t wire_bytes;     /* sent so far */
    uint64_t raw_bytes;      /* what plain frames would have taken */
} fc_progress;

void fc_progress_start(fc_progress *p, FILE *to, bool tty, uint32_t total);
/* One more frame went out: its file, particles and upload cost. */
void fc_progress_frame(fc_progress *p, const char *file, uint64_t particles, const fc_upload_stats *stats);
/* stream's summary line (after ending the bar on a terminal). */
void fc_progress_finish(fc_progress *p);

#endif
