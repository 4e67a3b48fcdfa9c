/* view_control.c — input and timers into render requests. */
#include "view_control.h"

#include <stdio.h>

#include "fc_frame.h"
#include "spacemouse_camera.h"
#include "view_camera.h"

static void send(fc_view_control *c, bool preview)
{
    c->sent.generation++;
    c->sent.preview = preview;
    fc_view_slots_put_request(c->slots, &c->sent);
}

void fc_view_control_init(fc_view_control *c, fc_view_slots *slots, const fc_camera *home, bool has_camera,
                          const fc_settings *settings, uint32_t file_count, double fps)
{
    *c = (fc_view_control){.slots = slots, .home = *home, .file_count = file_count, .fps = fps};
    c->sent.camera = *home;
    c->sent.has_camera = has_camera;
    c->sent.settings = *settings;
    c->playing = file_count > 1;
    c->window_height = (int)home->height;
    c->window_width = (int)home->width;
    c->session = !has_camera;
}

/* Any camera change: a preview now, the full image once still. */
static void moved(fc_view_control *c, double now_ms)
{
    c->sent.has_camera = true;
    c->moving = true;
    c->moved_ms = now_ms;
    send(c, true);
}

static void apply(fc_view_control *c, const fc_sm_camera_delta *d, double now_ms)
{
    if (fc_sm_camera_apply(d, &c->sent.camera, NULL) == FC_OK)
        moved(c, now_ms);
}

void fc_view_control_camera_moved(fc_view_control *c, const fc_camera *cam, double now_ms)
{
    c->sent.camera = *cam;
    moved(c, now_ms);
}

void fc_view_control_reset(fc_view_control *c, double now_ms)
{
    uint32_t w = c->sent.camera.width, h = c->sent.camera.height;
    c->sent.camera = c->home;
    c->sent.camera.width = w;
    c->sent.camera.height = h;
    moved(c, now_ms);
}

void fc_view_control_toggle_mode(fc_view_control *c)
{
    c->mode = fc_sm_mode_toggle(c->mode);
}

const char *fc_view_smoothing_name(fc_smoothing s)
{
    static const char *const names[] = {"none", "curvature", "bilateral", "binomial", "narrow"};
    return (unsigned)s < sizeof names / sizeof names[0] ? names[s] : "?";
}

static void cycle_smoothing(fc_view_control *c)
{
    fc_settings *s = &c->sent.settings;
    s->smoothing = (fc_smoothing)((s->smoothing + 1) % 5);
    s->iterations = fc_smoothing_default_iterations(s->smoothing);
    send(c, false);
}

static void step_frame(fc_view_control *c, double now_ms)
{
    if (c->file_count < 2)
        return;
    (void)now_ms;
    c->sent.frame_index = (c->sent.frame_index + 1) % c->file_count;
    c->frame_seen = false;
    send(c, c->moving);
}

static void key(fc_view_control *c, SDL_Keycode k, double now_ms)
{
    switch (k) {
    case SDLK_q:
    case SDLK_ESCAPE: c->quit = true; break;
    case SDLK_r: fc_view_control_reset(c, now_ms); break;
    case SDLK_f: fc_view_control_toggle_mode(c); break;
    case SDLK_s: cycle_smoothing(c); break;
    case SDLK_SPACE: c->playing = !c->playing && c->file_count > 1; break;
    case SDLK_n:
        c->playing = false;
        step_frame(c, now_ms);
        break;
    case SDLK_p:
        c->sent.screenshot++;
        send(c, false);
        break;
    default: break;
    }
}

/* Double-click: the worker reads the depth under the cursor and the next
 * image brings the point back (fc_view_control_picked). */
static void ask_pick(fc_view_control *c, int x, int y)
{
    c->sent.pick++;
    c->sent.pick_x = c->window_width > 1 ? (float)x / (float)(c->window_width - 1) : 0.5f;
    c->sent.pick_y = c->window_height > 1 ? (float)y / (float)(c->window_height - 1) : 0.5f;
    send(c, c->moving);
}

void fc_view_control_picked(fc_view_control *c, const fc_view_image *img, double now_ms)
{
    if (img->pick == 0 || img->pick != c->sent.pick || !img->picked)
        return;
    fc_view_set_pivot(&c->sent.camera, img->pivot);
    moved(c, now_ms);
}

static void motion(fc_view_control *c, const SDL_MouseMotionEvent *m, double now_ms)
{
    if (!c->drag_button || (m->xrel == 0 && m->yrel == 0))
        return;
    fc_view_drag kind = c->drag_button == SDL_BUTTON_LEFT ? FC_VIEW_DRAG_ORBIT : FC_VIEW_DRAG_PAN;
    if (kind == FC_VIEW_DRAG_ORBIT && c->mode == FC_SM_MODE_ORBIT) {
        if (fc_view_turntable(&c->sent.camera, m->xrel, m->yrel, c->window_height, NULL) == FC_OK)
            moved(c, now_ms);
        return;
    }
    fc_sm_camera_delta d = fc_view_drag_delta(kind, c->mode, &c->sent.camera, m->xrel, m->yrel, c->window_height);
    apply(c, &d, now_ms);
}

void fc_view_control_event(fc_view_control *c, const SDL_Event *e, double now_ms)
{
    switch (e->type) {
    case SDL_QUIT: c->quit = true; break;
    case SDL_KEYDOWN: key(c, e->key.keysym.sym, now_ms); break;
    case SDL_MOUSEBUTTONDOWN:
        if (e->button.button == SDL_BUTTON_LEFT && e->button.clicks == 2 && !c->session)
            ask_pick(c, e->button.x, e->button.y);
        else if (!c->drag_button)
            c->drag_button = e->button.button;
        break;
    case SDL_MOUSEBUTTONUP:
        if (e->button.button == c->drag_button)
            c->drag_button = 0;
        break;
    case SDL_MOUSEMOTION: motion(c, &e->motion, now_ms); break;
    case SDL_MOUSEWHEEL: {
        float clicks = (float)(e->wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e->wheel.y : e->wheel.y);
        fc_sm_camera_delta d = fc_view_wheel_delta(c->mode, clicks);
        apply(c, &d, now_ms);
        break;
    }
    default: break;
    }
}

void fc_view_control_resized(fc_view_control *c, int width, int height, double now_ms)
{
    if (width < 1 || height < 1)
        return;
    c->window_height = height;
    c->window_width = width;
    if ((uint32_t)width == c->sent.camera.width && (uint32_t)height == c->sent.camera.height)
        return;
    c->sent.camera.width = (uint32_t)width;
    c->sent.camera.height = (uint32_t)height;
    c->resize_pending = true;
    c->resized_ms = now_ms;
}

void fc_view_control_image_shown(fc_view_control *c, uint32_t frame_index, double now_ms)
{
    if (frame_index == c->sent.frame_index && !c->frame_seen) {
        c->frame_seen = true;
        c->frame_started_ms = now_ms;
    }
}

void fc_view_control_tick(fc_view_control *c, double now_ms)
{
    if (c->resize_pending && now_ms - c->resized_ms >= FC_VIEW_RESIZE_MS) {
        c->resize_pending = false;
        send(c, c->moving);
    }
    if (c->moving && now_ms - c->moved_ms >= FC_VIEW_STILL_MS) {
        c->moving = false;
        send(c, false);
    }
    /* The next frame once this one has shown for its time: a slow render
     * slows playback instead of skipping frames. */
    if (c->playing && c->frame_seen && now_ms - c->frame_started_ms >= 1000.0 / c->fps)
        step_frame(c, now_ms);
}

static int until(double due_ms, double now_ms)
{
    double left = due_ms - now_ms;
    return left <= 0 ? 0 : (int)left + 1;
}

int fc_view_control_wait_ms(const fc_view_control *c, double now_ms)
{
    int wait = 100;
    if (c->resize_pending && until(c->resized_ms + FC_VIEW_RESIZE_MS, now_ms) < wait)
        wait = until(c->resized_ms + FC_VIEW_RESIZE_MS, now_ms);
    if (c->moving && until(c->moved_ms + FC_VIEW_STILL_MS, now_ms) < wait)
        wait = until(c->moved_ms + FC_VIEW_STILL_MS, now_ms);
    if (c->playing && c->frame_seen && until(c->frame_started_ms + 1000.0 / c->fps, now_ms) < wait)
        wait = until(c->frame_started_ms + 1000.0 / c->fps, now_ms);
    return wait;
}

bool fc_view_control_settled(const fc_view_control *c)
{
    return !c->moving && !c->resize_pending && !c->sent.preview;
}
