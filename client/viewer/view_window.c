/* view_window.c — SDL2 window, renderer and the image texture. */
#include "view_window.h"

#include "fc_error.h"

fc_code fc_view_window_open(fc_view_window *w, uint32_t width, uint32_t height, fc_error *err)
{
    *w = (fc_view_window){0};
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
        return fc_error_set(err, FC_ERR_USAGE, "no display: %s", SDL_GetError());
    w->window = SDL_CreateWindow("fluidcast view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, (int)width,
                                 (int)height, SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI);
    if (w->window)
        w->renderer = SDL_CreateRenderer(w->window, -1, 0); /* accelerated when there is, else software */
    if (!w->renderer) {
        fc_error_set(err, FC_ERR_USAGE, "cannot open a window: %s", SDL_GetError());
        fc_view_window_close(w);
        return err ? err->code : FC_ERR_USAGE;
    }
    SDL_SetRenderDrawColor(w->renderer, 0, 0, 0, 255);
    SDL_RenderClear(w->renderer);
    SDL_RenderPresent(w->renderer);
    return FC_OK;
}

void fc_view_window_close(fc_view_window *w)
{
    if (w->texture)
        SDL_DestroyTexture(w->texture);
    if (w->renderer)
        SDL_DestroyRenderer(w->renderer);
    if (w->window)
        SDL_DestroyWindow(w->window);
    *w = (fc_view_window){0};
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

void fc_view_window_size(const fc_view_window *w, int *width, int *height)
{
    if (SDL_GetRendererOutputSize(w->renderer, width, height) != 0)
        SDL_GetWindowSize(w->window, width, height);
}

/* A texture of the image's size, recreated only when the size changes. */
static fc_code texture_for(fc_view_window *w, uint32_t width, uint32_t height, fc_error *err)
{
    if (w->texture && w->texture_width == width && w->texture_height == height)
        return FC_OK;
    if (w->texture)
        SDL_DestroyTexture(w->texture);
    /* RGBA32 is the byte order R, G, B, A whatever the host's endianness. */
    w->texture = SDL_CreateTexture(w->renderer, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING, (int)width,
                                   (int)height);
    if (!w->texture)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot create a %ux%u texture: %s", (unsigned)width,
                            (unsigned)height, SDL_GetError());
    /* Linear scaling: a half-size preview stretched over the window stays smooth. */
    SDL_SetTextureScaleMode(w->texture, SDL_ScaleModeLinear);
    w->texture_width = width;
    w->texture_height = height;
    return FC_OK;
}

void fc_view_window_redraw(fc_view_window *w)
{
    SDL_RenderClear(w->renderer);
    if (w->texture)
        SDL_RenderCopy(w->renderer, w->texture, NULL, NULL);
    SDL_RenderPresent(w->renderer);
}

fc_code fc_view_window_show(fc_view_window *w, const uint8_t *rgba, uint32_t width, uint32_t height, fc_error *err)
{
    fc_code code = texture_for(w, width, height, err);
    if (code != FC_OK)
        return code;
    if (SDL_UpdateTexture(w->texture, NULL, rgba, (int)width * 4) != 0)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot upload the image: %s", SDL_GetError());
    fc_view_window_redraw(w);
    return FC_OK;
}

void fc_view_window_set_hud(fc_view_window *w, const char *line) { SDL_SetWindowTitle(w->window, line); }

fc_code fc_view_window_save_bmp(fc_view_window *w, const char *path, fc_error *err)
{
    int width, height;
    fc_view_window_size(w, &width, &height);
    /* Read back the last drawn frame: draw it again first, since the back
     * buffer is undefined after a present. */
    SDL_RenderClear(w->renderer);
    if (w->texture)
        SDL_RenderCopy(w->renderer, w->texture, NULL, NULL);
    SDL_Surface *s = SDL_CreateRGBSurfaceWithFormat(0, width, height, 32, SDL_PIXELFORMAT_RGB888);
    fc_code code = FC_OK;
    if (!s)
        code = fc_error_set(err, FC_ERR_NOMEM, "%s", SDL_GetError());
    else if (SDL_RenderReadPixels(w->renderer, NULL, SDL_PIXELFORMAT_RGB888, s->pixels, s->pitch) != 0 ||
             SDL_SaveBMP(s, path) != 0)
        code = fc_error_set(err, FC_ERR_IO, "%s: %s", path, SDL_GetError());
    SDL_FreeSurface(s);
    SDL_RenderPresent(w->renderer);
    return code;
}
