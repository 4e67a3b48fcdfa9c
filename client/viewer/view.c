/* view.c — `fluidcast view`: setting up the window, the network worker and
 * the SpaceMouse, then the UI loop that ties them together. */
#include "view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli_connect.h"
#include "cli_particles.h"
#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_settings.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "up_axis.h"
#include "upright_framing.h"
#include "view_control.h"
#include "view_hud.h"
#include "view_link.h"
#include "view_options.h"
#include "view_script.h"
#include "view_spacemouse.h"
#include "view_window.h"

/* While the SpaceMouse is deflected the loop runs at about 60 frames a second. */
#define SPACEMOUSE_FRAME_MS 16

typedef struct viewer {
    fc_view_options opt;
    fc_view_window win;
    fc_view_slots slots;
    fc_view_link link;
    fc_view_control ctl;
    fc_view_spacemouse sm;
    fc_view_hud hud;
    Uint32 wake_type;             /* the SDL event the worker and the SpaceMouse wake the loop with */
    fc_view_image shown;          /* what is on screen (rgba released once uploaded) */
    bool have_image;
    fc_view_step *steps;
    int step_count, step;
    double step_started_ms;       /* when the current step first ran (sleep, wait) */
    int status;
    bool detached;                /* the worker outlives the loop (see fc_view_link_stop) */
    fc_view_session_state session_state; /* what the title last said of a followed session */
} viewer;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

/* Called from other threads: SDL_PushEvent is thread-safe. */
static void wake(void *ctx)
{
    SDL_Event e = {0};
    e.type = *(Uint32 *)ctx;
    SDL_PushEvent(&e);
}

/* A sequence's first frame gives the settings (radius) and the home
 * camera: framed on its fluid (framing_bounds.h), upright along the guessed
 * up axis. */
static int prepare_files(const fc_view_options *o, fc_frame *first, fc_settings *settings, fc_camera *home)
{
    int status = fc_cli_load_particles(o->files[0], &o->read, first);
    if (status != FC_EXIT_OK)
        return status;
    fc_cli_print_recentring(&o->recentring);
    fc_cli_choices chosen;
    fc_cli_complete_settings(settings, first, &chosen);
    fc_cli_complete_color_range(settings, first, fc_cli_setting_given(&o->settings, "color_range"), &chosen);
    fc_up_guess guess;
    float up[3] = {0, 0, 1};
    fc_error err;
    if (fc_up_axis_guess(first, &guess, &err) == FC_OK)
        fc_up_axis_vector(&guess, up);
    if (fc_frame_upright(first, o->width, o->height, up, home, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    return FC_EXIT_OK;
}

/* A session's frames are on the server only: it frames them itself until the
 * user moves, who then starts from this view of the unit box about the origin. */
static void session_home(const fc_view_options *o, fc_camera *home)
{
    *home = (fc_camera){.eye = {1.8f, -2.6f, 1.6f}, .target = {0, 0, 0}, .up = {0, 0, 1}, .fov_y_deg = 45.0f,
                        .width = o->width, .height = o->height};
}

/* The title: the HUD line of the image shown, with what a followed session
 * does; before any image, what the viewer waits for. */
static void update_title(viewer *v)
{
    char line[512];
    const char *session = v->opt.session;
    bool ended = v->session_state == FC_VIEW_SESSION_ENDED;
    if (!v->have_image) {
        if (!session || v->session_state == FC_VIEW_SESSION_NONE)
            return;
        if (ended)
            snprintf(line, sizeof line, "fluidcast view | session %s ended before its first frame; q quits", session);
        else
            snprintf(line, sizeof line, "fluidcast view | waiting for session %s", session);
    } else {
        char what[160];
        const fc_view_image *img = &v->shown;
        if (session && ended)
            snprintf(what, sizeof what, "session %s ended, frame %llu: drag to look around, q quits", session,
                     (unsigned long long)img->frame_number);
        else if (session)
            snprintf(what, sizeof what, "%s frame %llu", session, (unsigned long long)img->frame_number);
        else
            snprintf(what, sizeof what, "frame %u/%u%s", (unsigned)img->frame_index + 1, (unsigned)v->opt.file_count,
                     v->ctl.playing ? "" : " paused");
        fc_view_hud_line(&v->hud, img, what, v->ctl.mode, fc_view_smoothing_name(v->ctl.sent.settings.smoothing),
                         line, sizeof line);
    }
    fc_view_window_set_hud(&v->win, line);
    if (v->opt.log_camera)
        printf("title: %s\n", line), fflush(stdout);
}

/* The worker learnt something new about the session: said once on stderr and in the title. */
static void follow_session_state(viewer *v)
{
    fc_view_session_state state = fc_view_slots_session_state(&v->slots);
    if (state == v->session_state)
        return;
    v->session_state = state;
    if (state == FC_VIEW_SESSION_WAITING)
        fprintf(stderr, "fluidcast: waiting for session %s\n", v->opt.session);
    else if (state == FC_VIEW_SESSION_ENDED)
        fprintf(stderr, "fluidcast: session %s ended; drag to look around, q quits\n", v->opt.session);
    update_title(v);
}

static void show_image(viewer *v, fc_view_image *img)
{
    fc_error err;
    double now = now_ms();
    if (fc_view_window_show(&v->win, img->rgba, img->width, img->height, &err) != FC_OK)
        fprintf(stderr, "fluidcast: %s\n", err.message);
    fc_view_image_free(img);
    v->shown = *img;
    v->have_image = true;
    fc_view_hud_count(&v->hud, now);
    fc_view_control_image_shown(&v->ctl, img->frame_index, now);
    if (img->pick && v->opt.log_camera)
        printf("pick %u: %s %.6f %.6f %.6f\n", (unsigned)img->pick, img->picked ? "fluid at" : "no fluid",
               (double)img->pivot[0], (double)img->pivot[1], (double)img->pivot[2]);
    fc_view_control_picked(&v->ctl, img, now);
    update_title(v);
    if (v->opt.log_camera)
        printf("shown %llu: %ux%u frame %u%s\n", (unsigned long long)img->generation, (unsigned)img->width,
               (unsigned)img->height, (unsigned)img->frame_index, img->preview ? " preview" : ""), fflush(stdout);
}

static void handle_window(viewer *v, const SDL_WindowEvent *w)
{
    if (w->event == SDL_WINDOWEVENT_SIZE_CHANGED) {
        int width, height;
        fc_view_window_size(&v->win, &width, &height);
        fc_view_control_resized(&v->ctl, width, height, now_ms());
        fc_view_window_redraw(&v->win);
    } else if (w->event == SDL_WINDOWEVENT_EXPOSED) {
        fc_view_window_redraw(&v->win);
    }
}

static void handle_event(viewer *v, const SDL_Event *e)
{
    if (e->type == v->wake_type)
        return; /* the loop looks at the image slot and the SpaceMouse after every batch */
    if (e->type == SDL_WINDOWEVENT)
        handle_window(v, &e->window);
    else
        fc_view_control_event(&v->ctl, e, now_ms());
}

static void spacemouse_frame(viewer *v)
{
    fc_camera cam = v->ctl.sent.camera;
    fc_view_sm_result r = fc_view_spacemouse_frame(&v->sm, v->ctl.mode, &cam);
    if (r.toggle_mode)
        fc_view_control_toggle_mode(&v->ctl);
    if (r.reset)
        fc_view_control_reset(&v->ctl, now_ms());
    else if (r.moved)
        fc_view_control_camera_moved(&v->ctl, &cam, now_ms());
}

/* Whether the image at rest has arrived; past the step's limit the viewer
 * ends with status 7 and what it waited for (test hook). */
static bool wait_over(viewer *v, int limit_ms)
{
    if (v->step_started_ms == 0.0)
        v->step_started_ms = now_ms();
    bool settled = fc_view_control_settled(&v->ctl);
    bool current = v->have_image && v->shown.generation == v->ctl.sent.generation;
    if (settled && current) {
        v->step_started_ms = 0.0;
        return true;
    }
    if (now_ms() - v->step_started_ms >= limit_ms) {
        v->status = fc_cli_fail(FC_EXIT_CONNECTION,
                                "--test-script: wait: no image at rest after %d s (camera %s, %s, request %llu)",
                                limit_ms / 1000, settled ? "still" : "moving",
                                v->have_image ? "an older image shown" : "no image yet",
                                (unsigned long long)v->ctl.sent.generation);
        v->ctl.quit = true;
    }
    return false;
}

/* One step of the test script, when its condition holds. */
static void script_step(viewer *v)
{
    if (v->step >= v->step_count)
        return;
    const fc_view_step *s = &v->steps[v->step];
    int width, height;
    fc_view_window_size(&v->win, &width, &height);
    fc_error err;
    switch (s->kind) {
    case FC_VIEW_STEP_WAIT:
        if (!wait_over(v, s->dx))
            return;
        break;
    case FC_VIEW_STEP_DRAG: fc_view_script_push_drag(SDL_BUTTON_LEFT, width / 2, height / 2, s->dx, s->dy); break;
    case FC_VIEW_STEP_PAN: fc_view_script_push_drag(SDL_BUTTON_RIGHT, width / 2, height / 2, s->dx, s->dy); break;
    case FC_VIEW_STEP_KEY: fc_view_script_push_key(s->key); break;
    case FC_VIEW_STEP_DCLICK: fc_view_script_push_double_click(width / 2 + s->dx, height / 2 + s->dy); break;
    case FC_VIEW_STEP_SHOT:
        if (fc_view_window_save_bmp(&v->win, s->path, &err) != FC_OK)
            fprintf(stderr, "fluidcast: %s\n", err.message);
        else
            printf("shot: %s (%dx%d)\n", s->path, width, height), fflush(stdout);
        break;
    case FC_VIEW_STEP_SLEEP:
        if (v->step_started_ms == 0.0)
            v->step_started_ms = now_ms();
        if (now_ms() - v->step_started_ms < s->dx)
            return;
        v->step_started_ms = 0.0;
        break;
    case FC_VIEW_STEP_RESIZE: fc_view_script_resize(v->win.window, s->dx, s->dy); break;
    case FC_VIEW_STEP_RTT:
        printf("round trip: %.1f ms %ux%u\n", v->shown.round_trip_ms, v->shown.width, v->shown.height);
        fflush(stdout);
        break;
    case FC_VIEW_STEP_QUIT: v->ctl.quit = true; break;
    case FC_VIEW_STEP_DONE: break;
    }
    v->step++;
}

static int wait_ms(const viewer *v)
{
    int wait = fc_view_control_wait_ms(&v->ctl, now_ms());
    if (fc_view_spacemouse_moving(&v->sm) && wait > SPACEMOUSE_FRAME_MS)
        wait = SPACEMOUSE_FRAME_MS;
    if (v->step < v->step_count && wait > 10)
        wait = 10;
    return wait;
}

/* True when the worker failed (the loop ends). The end of a session is no
 * failure: the window stays on the last image, whose camera still works. */
static bool worker_failed(viewer *v)
{
    char message[FC_ERROR_MESSAGE_MAX];
    int status = fc_view_slots_failure(&v->slots, message, sizeof message);
    if (message[0] == '\0')
        return false;
    v->status = fc_cli_fail(status, "%s: %s", v->opt.server, message);
    return true;
}

static void loop(viewer *v)
{
    while (!v->ctl.quit) {
        SDL_Event e;
        if (SDL_WaitEventTimeout(&e, wait_ms(v))) {
            handle_event(v, &e);
            while (SDL_PollEvent(&e))
                handle_event(v, &e);
        }
        fc_view_image img;
        if (fc_view_slots_take_image(&v->slots, &img))
            show_image(v, &img);
        follow_session_state(v);
        if (worker_failed(v))
            return;
        spacemouse_frame(v);
        fc_view_control_tick(&v->ctl, now_ms());
        script_step(v);
    }
}

/* Connects, opens the window and starts the worker; the loop runs between. */
static int run(viewer *v, fc_frame *first, const fc_settings *settings, const fc_camera *home)
{
    fc_error err;
    fc_connect_options connect = fc_cli_connect_options("fluidcast view");
    fc_client *client;
    if (fc_cli_connect(v->opt.server, v->opt.session, &connect, &client, &err) != FC_OK)
        return fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s", err.message);
    if (fc_view_window_open(&v->win, v->opt.width, v->opt.height, &err) != FC_OK) {
        fc_client_close(client);
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    }
    if (fc_view_slots_init(&v->slots, &err) != FC_OK) {
        fc_client_close(client);
        fc_view_window_close(&v->win);
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    }
    fc_view_control_init(&v->ctl, &v->slots, home, v->opt.session == NULL, settings, v->opt.file_count, v->opt.fps);
    int width, height;
    fc_view_window_size(&v->win, &width, &height);
    fc_view_control_resized(&v->ctl, width, height, now_ms());
    v->ctl.resize_pending = false; /* the first request has the size already */
    v->ctl.sent.generation = 1;
    fc_view_slots_put_request(&v->slots, &v->ctl.sent);
    fc_view_link_config link = {.session = v->opt.session, .files = v->opt.files, .file_count = v->opt.file_count,
                                .first_frame = *first, .read = &v->opt.read, .log_camera = v->opt.log_camera,
                                .width = (uint32_t)width, .height = (uint32_t)height, .format = v->opt.format,
                                .wake = wake, .wake_ctx = &v->wake_type};
    *first = (fc_frame){0}; /* the link owns it now */
    if (fc_view_link_start(&v->link, &link, &v->slots, client, &err) != FC_OK)
        v->status = fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    else {
        if (!v->opt.no_spacemouse)
            fc_view_spacemouse_start(&v->sm, wake, &v->wake_type);
        loop(v);
        fc_view_spacemouse_stop(&v->sm);
    }
    bool joined = fc_view_link_stop(&v->link, 2000);
    fc_view_window_close(&v->win);
    if (joined)
        fc_view_slots_destroy(&v->slots);
    v->detached = !joined;
    return v->status;
}

static int view(viewer *v)
{
    fc_frame first = {0};
    fc_settings settings = v->opt.settings.values;
    fc_camera home;
    if (v->opt.session)
        session_home(&v->opt, &home);
    else if ((v->status = prepare_files(&v->opt, &first, &settings, &home)) != FC_EXIT_OK) {
        fc_frame_free(&first);
        return v->status;
    }
    if (SDL_Init(SDL_INIT_EVENTS) != 0) {
        fc_frame_free(&first);
        return fc_cli_fail(FC_EXIT_USAGE, "SDL: %s", SDL_GetError());
    }
    v->wake_type = SDL_RegisterEvents(1);
    int status = run(v, &first, &settings, &home);
    fc_frame_free(&first);
    SDL_Quit();
    return status;
}

static int view_main(viewer *v, int argc, char **argv)
{
    fc_error err;
    if (fc_view_parse(argc, argv, &v->opt, &err) != FC_OK) {
        fc_view_options_free(&v->opt);
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    }
    if (v->opt.help) {
        fc_view_print_help(stdout);
        fc_view_options_free(&v->opt);
        return FC_EXIT_OK;
    }
    if (v->opt.test_script && fc_view_script_parse(v->opt.test_script, &v->steps, &v->step_count, &err) != FC_OK) {
        fc_view_options_free(&v->opt);
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    }
    int status = view(v);
    free(v->steps);
    fc_view_options_free(&v->opt);
    return status;
}

int fc_view_main(int argc, char **argv)
{
    viewer *v = calloc(1, sizeof *v);
    if (!v)
        return fc_cli_fail(FC_EXIT_USAGE, "out of memory");
    int status = view_main(v, argc, argv);
    /* A worker left waiting on a session's next image still reads v's slots
     * until the process exits: then v is not freed. */
    if (!v->detached)
        free(v);
    return status;
}
