/* view_hud.h — the HUD line: frames per second on screen, the server's stage
 * times and the round-trip latency of the newest image. Shown as the window's
 * title, since no font library is linked. */
#ifndef FC_VIEW_HUD_H
#define FC_VIEW_HUD_H

#include <stddef.h>
#include <stdint.h>

#include "spacemouse_motion.h"
#include "view_slot.h"

typedef struct fc_view_hud {
    double window_start_ms;       /* start of the current fps window */
    uint32_t window_images;
    double fps;
} fc_view_hud;

/* Counts an image shown at now_ms (fps over windows of half a second). */
void fc_view_hud_count(fc_view_hud *hud, double now_ms);

/* The line for the newest image and the viewer's state. */
void fc_view_hud_line(const fc_view_hud *hud, const fc_view_image *img, const char *what, fc_sm_mode mode,
                      const char *smoothing, char *out, size_t size);

#endif
