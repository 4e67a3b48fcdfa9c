/* view_window.h — the SDL2 window: a streaming texture the newest image is
 * uploaded to and stretched over the window, the HUD in the window's title
 * (no font library is linked, so no text is drawn into the picture), and a
 * read-back of what is on screen for tests. */
#ifndef FC_VIEW_WINDOW_H
#define FC_VIEW_WINDOW_H

#include <SDL.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_view_window {
    SDL_Window *window;
    SDL_Renderer *renderer;
    SDL_Texture *texture;
    uint32_t texture_width, texture_height;
} fc_view_window;

fc_code fc_view_window_open(fc_view_window *w, uint32_t width, uint32_t height, fc_error *err);
void fc_view_window_close(fc_view_window *w);

/* The window's drawable size in pixels. */
void fc_view_window_size(const fc_view_window *w, int *width, int *height);

/* Uploads RGBA8 rows (top to bottom) and draws them over the whole window. */
fc_code fc_view_window_show(fc_view_window *w, const uint8_t *rgba, uint32_t width, uint32_t height, fc_error *err);

/* Redraws the last texture (after an expose or a resize). */
void fc_view_window_redraw(fc_view_window *w);

void fc_view_window_set_hud(fc_view_window *w, const char *line);

/* Writes what the window shows as a BMP (SDL_RenderReadPixels). */
fc_code fc_view_window_save_bmp(fc_view_window *w, const char *path, fc_error *err);

#endif
