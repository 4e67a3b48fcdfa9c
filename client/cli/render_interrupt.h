/* render_interrupt.h — Ctrl-C (SIGINT) and SIGTERM during `fluidcast render`:
 * the frame in flight is finished, then the render stops and a video gets its
 * trailer, so an interrupted render leaves a video that plays (and whole image
 * files, to resume with --skip-existing). A second signal ends the process at
 * once (the default action is restored after the first). */
#ifndef FC_RENDER_INTERRUPT_H
#define FC_RENDER_INTERRUPT_H

#include <stdbool.h>

/* The exit status of an interrupted render: 128 + the signal, as shells report. */
#define FC_RENDER_INTERRUPT_STATUS_BASE 128

/* Installs the handlers (without SA_RESTART; libfluidcast retries calls
 * that a signal interrupts, so the frame in flight completes). */
void fc_render_interrupt_install(void);

/* The signal that arrived, 0 when none. */
int fc_render_interrupted(void);

#endif
