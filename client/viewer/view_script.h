/* view_script.h — the viewer's test hook (--test-script): a list of
 * ';'-separated commands that drive the window through the same SDL events a
 * user makes, so tests under Xvfb exercise the real event handling:
 *     wait [S]        until the image on screen answers the latest request at
 *                     full size (the camera has been still and it arrived);
 *                     after S seconds (default 60) without it the viewer
 *                     exits with status 7 and says what it waited for, so a
 *                     test fails with a reason instead of its own timeout
 *     drag DX DY      a left-button drag by DX, DY pixels from the centre
 *     pan DX DY       the same with the right button
 *     dclick DX DY    a left double-click DX, DY pixels from the centre
 *     key K           a key press (one character: r f s n p q, or "space")
 *     shot FILE.bmp   writes what the window shows
 *     sleep MS        lets MS milliseconds pass (events keep being handled)
 *     resize W H      asks for a W x H window (SDL_SetWindowSize), as a user's
 *                     drag of its border does
 *     rtt             prints the round trip of the image on screen: "round
 *                     trip: MS ms WxH" (its request sent -> it decoded;
 *                     bench/viewer/viewer_latency.sh reads it after a wait)
 *     quit            ends the viewer (exit status 0)
 * Not meant for users; documented in --help as a test hook. */
#ifndef FC_VIEW_SCRIPT_H
#define FC_VIEW_SCRIPT_H

#include <SDL.h>
#include <stdbool.h>

#include "fluidcast_types.h"

typedef enum fc_view_step_kind {
    FC_VIEW_STEP_DONE = 0,        /* the script is over */
    FC_VIEW_STEP_WAIT,
    FC_VIEW_STEP_DRAG,
    FC_VIEW_STEP_PAN,
    FC_VIEW_STEP_KEY,
    FC_VIEW_STEP_DCLICK,
    FC_VIEW_STEP_SHOT,
    FC_VIEW_STEP_SLEEP,
    FC_VIEW_STEP_RESIZE,
    FC_VIEW_STEP_RTT,
    FC_VIEW_STEP_QUIT
} fc_view_step_kind;

typedef struct fc_view_step {
    fc_view_step_kind kind;
    int dx, dy;                   /* drag, pan; dx: milliseconds of sleep or of wait's limit; resize: W, H */
    int key;                      /* SDL keycode */
    char path[256];
} fc_view_step;

/* Parses the whole script up front, so a typo fails before the window opens.
 * *steps (free()) gets *count steps. */
fc_code fc_view_script_parse(const char *text, fc_view_step **steps, int *count, fc_error *err);

/* Queues the SDL events of a drag with `button` (SDL_BUTTON_LEFT/RIGHT)
 * starting at (x, y), in ten motions. */
void fc_view_script_push_drag(int button, int x, int y, int dx, int dy);
void fc_view_script_push_key(int key);
void fc_view_script_push_double_click(int x, int y);
/* Resizes the window; its SDL_WINDOWEVENT_SIZE_CHANGED then comes through
 * the event queue like a user's resize. */
void fc_view_script_resize(SDL_Window *window, int width, int height);

#endif
