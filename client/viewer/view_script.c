/* view_script.c — parsing the test hook's script and injecting its events. */
#include "view_script.h"

#include <SDL.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

#define DRAG_MOTIONS 10
#define WAIT_LIMIT_S 60

static int key_named(const char *name)
{
    if (strcmp(name, "space") == 0)
        return SDLK_SPACE;
    if (strcmp(name, "esc") == 0)
        return SDLK_ESCAPE;
    return strlen(name) == 1 ? name[0] : -1;
}

static fc_code parse_step(const char *text, fc_view_step *s, fc_error *err)
{
    char word[16] = "", arg[256] = "";
    int n = sscanf(text, " %15s %255s", word, arg);
    memset(s, 0, sizeof *s);
    int seconds = WAIT_LIMIT_S;
    if (strcmp(word, "wait") == 0 && (n == 1 || (sscanf(text, " %*s %d", &seconds) == 1 && seconds >= 0))) {
        s->kind = FC_VIEW_STEP_WAIT;
        s->dx = seconds * 1000;
    }
    else if (n >= 1 && strcmp(word, "quit") == 0)
        s->kind = FC_VIEW_STEP_QUIT;
    else if (n == 1 && strcmp(word, "rtt") == 0)
        s->kind = FC_VIEW_STEP_RTT;
    else if ((strcmp(word, "drag") == 0 || strcmp(word, "pan") == 0 || strcmp(word, "dclick") == 0) &&
             sscanf(text, " %*s %d %d", &s->dx, &s->dy) == 2)
        s->kind = word[1] == 'c' ? FC_VIEW_STEP_DCLICK : word[0] == 'd' ? FC_VIEW_STEP_DRAG : FC_VIEW_STEP_PAN;
    else if (strcmp(word, "resize") == 0 && sscanf(text, " %*s %d %d", &s->dx, &s->dy) == 2 && s->dx > 0 &&
             s->dy > 0)
        s->kind = FC_VIEW_STEP_RESIZE;
    else if (strcmp(word, "sleep") == 0 && sscanf(text, " %*s %d", &s->dx) == 1 && s->dx >= 0)
        s->kind = FC_VIEW_STEP_SLEEP;
    else if (n == 2 && strcmp(word, "key") == 0 && (s->key = key_named(arg)) >= 0)
        s->kind = FC_VIEW_STEP_KEY;
    else if (n == 2 && strcmp(word, "shot") == 0) {
        s->kind = FC_VIEW_STEP_SHOT;
        snprintf(s->path, sizeof s->path, "%s", arg);
    } else
        return fc_error_set(err, FC_ERR_USAGE, "--test-script: cannot read \"%s\"", text);
    return FC_OK;
}

fc_code fc_view_script_parse(const char *text, fc_view_step **steps, int *count, fc_error *err)
{
    *steps = NULL;
    *count = 0;
    char *copy = strdup(text);
    fc_view_step *list = calloc(strlen(text) / 2 + 2, sizeof *list); /* a step takes >= 2 characters */
    fc_code code = copy && list ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "out of memory");
    int n = 0;
    char *save = NULL;
    for (char *part = code == FC_OK ? strtok_r(copy, ";", &save) : NULL; part && code == FC_OK;
         part = strtok_r(NULL, ";", &save)) {
        if (strspn(part, " \t") == strlen(part))
            continue;
        code = parse_step(part, &list[n++], err);
    }
    free(copy);
    if (code != FC_OK) {
        free(list);
        return code;
    }
    *steps = list;
    *count = n;
    return FC_OK;
}

static void push_button(Uint32 type, int button, int x, int y, int clicks)
{
    SDL_Event e = {0};
    e.button.type = type;
    e.button.button = (Uint8)button;
    e.button.state = type == SDL_MOUSEBUTTONDOWN ? SDL_PRESSED : SDL_RELEASED;
    e.button.clicks = (Uint8)clicks;
    e.button.x = x;
    e.button.y = y;
    SDL_PushEvent(&e);
}

void fc_view_script_push_drag(int button, int x, int y, int dx, int dy)
{
    push_button(SDL_MOUSEBUTTONDOWN, button, x, y, 1);
    int done_x = 0, done_y = 0;
    for (int i = 1; i <= DRAG_MOTIONS; i++) {
        SDL_Event e = {0};
        e.motion.type = SDL_MOUSEMOTION;
        e.motion.state = SDL_BUTTON(button);
        e.motion.xrel = dx * i / DRAG_MOTIONS - done_x;
        e.motion.yrel = dy * i / DRAG_MOTIONS - done_y;
        done_x += e.motion.xrel;
        done_y += e.motion.yrel;
        e.motion.x = x + done_x;
        e.motion.y = y + done_y;
        SDL_PushEvent(&e);
    }
    push_button(SDL_MOUSEBUTTONUP, button, x + dx, y + dy, 1);
}

void fc_view_script_push_key(int key)
{
    SDL_Event e = {0};
    e.key.type = SDL_KEYDOWN;
    e.key.state = SDL_PRESSED;
    e.key.keysym.sym = key;
    SDL_PushEvent(&e);
}

void fc_view_script_push_double_click(int x, int y)
{
    push_button(SDL_MOUSEBUTTONDOWN, SDL_BUTTON_LEFT, x, y, 1);
    push_button(SDL_MOUSEBUTTONUP, SDL_BUTTON_LEFT, x, y, 1);
    push_button(SDL_MOUSEBUTTONDOWN, SDL_BUTTON_LEFT, x, y, 2);
    push_button(SDL_MOUSEBUTTONUP, SDL_BUTTON_LEFT, x, y, 2);
}

void fc_view_script_resize(SDL_Window *window, int width, int height)
{
    SDL_SetWindowSize(window, width, height);
}
