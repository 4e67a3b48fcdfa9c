/* view_link.c — the network worker: a sequence's frames rendered on request,
 * or a session's images as they come. */
#include "view_link.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli_report.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "output_file.h"
#include "particle_reader.h"
#include "view_camera.h"
#include "view_decode.h"

/* How long a session's worker waits for the server's next message before it
 * looks for a camera change again: short beside a render, so a drag goes out
 * at once, and the idle worker wakes 100 times a second at most. */
#define REQUEST_POLL_MS 10u

/* What the worker remembers of what it sent, to send only changes. */
typedef struct link_state {
    uint32_t loaded;              /* frame index on the server; UINT32_MAX: none */
    bool settings_sent;
    fc_settings settings;
    uint32_t screenshot_done;
    uint32_t pick_done;
    double sent_ms;               /* when the last camera/settings went out */
    fc_view_decoder *decoder;
    bool keyframe_asked;          /* H.264: a key frame was asked for and has not come yet */
} link_state;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static void give_up(fc_view_link *link, int exit_status, const char *fmt, const char *detail)
{
    char message[FC_ERROR_MESSAGE_MAX];
    snprintf(message, sizeof message, fmt, detail);
    fc_view_slots_fail(link->slots, exit_status, message);
    link->config.wake(link->config.wake_ctx);
}

static int client_exit(const fc_error *err) { return fc_cli_exit_for_client_error(err->code); }

/* H.264 pictures (4:2:0) have even sides: one pixel less, the window scales it. */
static uint32_t even(uint32_t side)
{
    return side > 2 ? side & ~1u : 2;
}

/* The camera the daemon renders with: the window's, halved while moving. */
static fc_camera render_camera(const fc_view_link *link, const fc_view_request *r)
{
    fc_camera cam = r->camera;
    if (r->preview) {
        cam.width = cam.width / 2 ? cam.width / 2 : 1;
        cam.height = cam.height / 2 ? cam.height / 2 : 1;
    }
    if (link->config.format == FC_FORMAT_H264) {
        cam.width = even(cam.width);
        cam.height = even(cam.height);
    }
    return cam;
}

static void log_camera(const fc_view_link *link, const fc_view_request *r, const fc_camera *c)
{
    if (!link->config.log_camera)
        return;
    printf("camera %llu: eye %.6f %.6f %.6f target %.6f %.6f %.6f up %.6f %.6f %.6f size %ux%u%s\n",
           (unsigned long long)r->generation, (double)c->eye[0], (double)c->eye[1], (double)c->eye[2],
           (double)c->target[0], (double)c->target[1], (double)c->target[2], (double)c->up[0], (double)c->up[1],
           (double)c->up[2], (unsigned)c->width, (unsigned)c->height, r->preview ? " preview" : "");
    fflush(stdout);
}

/* Camera (when the viewer has one) and changed settings. */
static fc_code send_view(fc_view_link *link, link_state *st, const fc_view_request *r, fc_error *err)
{
    if (!st->settings_sent || memcmp(&st->settings, &r->settings, sizeof r->settings) != 0) {
        fc_code code = fc_client_set_settings(link->client, &r->settings, err);
        if (code != FC_OK)
            return code;
        st->settings = r->settings;
        st->settings_sent = true;
    }
    st->sent_ms = now_ms();
    if (!r->has_camera)
        return FC_OK;
    fc_camera cam = render_camera(link, r);
    log_camera(link, r, &cam);
    return fc_client_set_camera(link->client, &cam, err);
}

static fc_render_request image_request(const fc_view_link *link)
{
    return (fc_render_request){.format = link->config.format, .quality = 90, .aov = FC_AOV_COLOR};
}

static fc_code push_frame(fc_view_link *link, link_state *st, uint32_t index, fc_error *err)
{
    fc_frame frame = {0};
    fc_code code = FC_OK;
    if (index == 0 && link->config.first_frame.count)
        frame = link->config.first_frame; /* kept: the sequence loops back to it */
    else
        code = fc_read_particles_with(link->config.files[index], link->config.read, &frame, err);
    if (code == FC_OK)
        code = fc_frame_validate(&frame, err);
    if (code == FC_OK)
        code = fc_client_send_frame(link->client, &frame, err);
    if (frame.positions != link->config.first_frame.positions)
        fc_frame_free(&frame);
    if (code == FC_OK)
        st->loaded = index;
    return code;
}

/* The lossless screenshot: a PNG rendered at the current camera, full size. */
static fc_code screenshot(fc_view_link *link, const fc_view_request *r, fc_error *err)
{
    fc_view_request full = *r;
    full.preview = false;
    fc_camera cam = render_camera(link, &full);
    fc_code code = fc_client_set_camera(link->client, &cam, err);
    fc_image_result img = {0};
    fc_render_request png = {.format = FC_FORMAT_PNG, .quality = 90, .aov = FC_AOV_COLOR};
    if (code == FC_OK)
        code = fc_client_render(link->client, &png, &img, err);
    char path[64];
    snprintf(path, sizeof path, "fluidcast-view-%04u.png", (unsigned)r->screenshot);
    if (code == FC_OK)
        code = fc_output_write(path, img.data, img.size, err);
    if (code == FC_OK)
        printf("screenshot: %s (%ux%u PNG)\n", path, (unsigned)img.width, (unsigned)img.height), fflush(stdout);
    fc_image_result_free(&img);
    return code;
}

/* The point under the cursor: one quarter-size depth AOV (linear view depth
 * along the view axis, 0 where there is no fluid), read at the pixel and
 * taken back along the pixel's ray. Cheap next to a colour render. */
static fc_code pick(fc_view_link *link, const fc_view_request *r, fc_view_image *out, fc_error *err)
{
    fc_camera cam = r->camera;
    cam.width = cam.width / 4 ? cam.width / 4 : 1;
    cam.height = cam.height / 4 ? cam.height / 4 : 1;
    fc_code code = fc_client_set_camera(link->client, &cam, err);
    fc_image_result img = {0};
    fc_render_request depth = {.format = FC_FORMAT_RAW, .quality = 90, .aov = FC_AOV_DEPTH};
    if (code == FC_OK)
        code = fc_client_render(link->client, &depth, &img, err);
    if (code == FC_OK && img.size != (size_t)img.width * img.height * sizeof(float))
        code = fc_error_set(err, FC_ERR_PROTOCOL, "depth AOV of %zu bytes for %ux%u", img.size,
                            (unsigned)img.width, (unsigned)img.height);
    if (code == FC_OK) {
        uint32_t x = (uint32_t)(r->pick_x * (float)(img.width - 1) + 0.5f);
        uint32_t y = (uint32_t)(r->pick_y * (float)(img.height - 1) + 0.5f);
        float d;
        memcpy(&d, img.data + ((size_t)y * img.width + x) * sizeof d, sizeof d);
        out->pick = r->pick;
        out->picked = d > 0.0f && fc_view_unproject(&r->camera, r->pick_x, r->pick_y, d, out->pivot);
    }
    fc_image_result_free(&img);
    return code;
}

static fc_code render_files(fc_view_link *link, link_state *st, const fc_view_request *r, fc_error *err)
{
    fc_code code = FC_OK;
    if (r->frame_index != st->loaded)
        code = push_frame(link, st, r->frame_index, err);
    if (code == FC_OK && r->screenshot != st->screenshot_done) {
        st->screenshot_done = r->screenshot;
        if ((code = screenshot(link, r, err)) != FC_OK)
            return code;
    }
    fc_view_image out = {.generation = r->generation, .frame_index = r->frame_index, .preview = r->preview};
    if (code == FC_OK && r->pick != st->pick_done) {
        st->pick_done = r->pick;
        code = pick(link, r, &out, err);
    }
    if (code == FC_OK)
        code = send_view(link, st, r, err);
    fc_image_result img = {0};
    fc_render_request request = image_request(link);
    if (code == FC_OK)
        code = fc_client_render(link->client, &request, &img, err);
    if (code == FC_OK)
        code = fc_view_decoder_decode(st->decoder, &img, &out, err);
    fc_image_result_free(&img);
    if (code == FC_OK && !out.rgba)
        code = fc_error_set(err, FC_ERR_PROTOCOL, "the server's H.264 image shows nothing");
    if (code != FC_OK)
        return code;
    out.round_trip_ms = now_ms() - st->sent_ms;
    fc_view_slots_put_image(link->slots, &out);
    link->config.wake(link->config.wake_ctx);
    return FC_OK;
}

static void run_files(fc_view_link *link, link_state *state)
{
    link_state st = *state;
    uint64_t done = 0;
    fc_view_request r;
    bool stop = false;
    while (fc_view_slots_wait_request(link->slots, done, -1, &r, &stop)) {
        done = r.generation;
        fc_error err;
        if (render_files(link, &st, &r, &err) != FC_OK) {
            give_up(link, client_exit(&err), "%s", err.message);
            return;
        }
    }
}

/* Decodes a session's image; an H.264 access unit that shows nothing (its
 * reference was lost) asks the server for a key frame, once until it comes. */
static fc_code decode_stream_image(fc_view_link *link, link_state *st, fc_stream_image *img, fc_view_image *out,
                                   fc_error *err)
{
    fc_code code = fc_view_decoder_decode(st->decoder, &img->image, out, err);
    if (img->keyframe)
        st->keyframe_asked = false;
    if (code != FC_OK || out->rgba || img->image.format != FC_FORMAT_H264 || st->keyframe_asked)
        return code;
    st->keyframe_asked = true;
    return fc_client_request_keyframe(link->client, err);
}

static void set_session_state(fc_view_link *link, fc_view_session_state state)
{
    fc_view_slots_set_session_state(link->slots, state);
    link->config.wake(link->config.wake_ctx);
}

/* Decodes a session's image and hands it to the UI; false on an error (in
 * *err). *drawn: whether it gave a picture (an H.264 unit whose reference was
 * lost gives none; its key frame follows). */
static bool show_stream_image(fc_view_link *link, link_state *st, fc_stream_image *img, uint64_t generation,
                              bool preview, bool *drawn, fc_error *err)
{
    fc_view_image out = {.generation = generation, .frame_number = img->frame_number, .preview = preview};
    *drawn = false;
    fc_code code = decode_stream_image(link, st, img, &out, err);
    if (code != FC_OK)
        return false;
    if (!out.rgba)
        return true;
    *drawn = true;
    out.round_trip_ms = img->view_change ? now_ms() - st->sent_ms : -1.0;
    fc_view_slots_put_image(link->slots, &out);
    link->config.wake(link->config.wake_ctx);
    return true;
}

/* The session ended: its last frame stays on the server for this viewer
 * (PROTOCOL.md 10.1), and nothing comes unasked any more. Each change of the
 * view goes out at once and its image (flag view_change) is read back, after
 * any refresh of the one before. Without a frame there is nothing to turn:
 * the worker waits for the UI to stop it. An H.264 view image that cannot be
 * decoded (its reference was lost) is answered by the key frame asked for. */
static bool follow_ended(fc_view_link *link, link_state *st, uint64_t done, bool have_frame, fc_error *err)
{
    for (;;) {
        fc_view_request r;
        bool stop = false;
        if (!fc_view_slots_wait_request(link->slots, done, -1, &r, &stop))
            return stop;
        done = r.generation;
        if (!have_frame)
            continue;
        if (send_view(link, st, &r, err) != FC_OK)
            return false;
        bool answered = false;
        while (!answered) {
            fc_stream_image img;
            if (fc_client_next_image(link->client, &img, err) != FC_OK)
                return false;
            bool drawn;
            bool ok = show_stream_image(link, st, &img, r.generation, r.preview, &drawn, err);
            answered = img.view_change && drawn;
            fc_stream_image_free(&img);
            if (!ok)
                return false;
        }
    }
}

/* A session: images come when the producer publishes (or after a view
 * change); a changed camera goes out as soon as the UI makes it, also while
 * a slow producer's next frame is minutes away: the worker reads an image
 * only once one is arriving, and looks for the UI's requests every
 * REQUEST_POLL_MS meanwhile. Until the first image the session waits (for its
 * producer or its first frame); after its end the viewer stays on the last
 * frame (follow_ended). */
static void run_session(fc_view_link *link, link_state *state)
{
    fc_error err;
    fc_render_request request = image_request(link);
    uint32_t width = link->config.width, height = link->config.height;
    if (request.format == FC_FORMAT_H264) {
        width = even(width);
        height = even(height);
    }
    link_state st = *state;
    /* The settings go out before SUBSCRIBE: the session's current frame is
     * rendered for this viewer at once, and with the server's defaults it
     * would show a look the user did not ask for until the first view change. */
    fc_view_request first;
    bool stopping = false;
    if (fc_view_slots_wait_request(link->slots, 0, 0, &first, &stopping) && !st.settings_sent) {
        if (fc_client_set_settings(link->client, &first.settings, &err) != FC_OK) {
            give_up(link, client_exit(&err), "%s", err.message);
            return;
        }
        st.settings = first.settings;
        st.settings_sent = true;
    }
    fc_session_status status;
    if (fc_client_subscribe(link->client, link->config.session, &request, width, height, &status, &err) != FC_OK) {
        give_up(link, client_exit(&err), "%s", err.message);
        return;
    }
    bool have_frame = status.last_frame != 0;
    set_session_state(link, have_frame ? FC_VIEW_SESSION_LIVE : FC_VIEW_SESSION_WAITING);
    uint64_t done = 0, shown = 0;
    bool preview = false;
    for (;;) {
        fc_view_request r;
        bool stop = false;
        if (fc_view_slots_wait_request(link->slots, done, 0, &r, &stop)) {
            done = r.generation;
            if (send_view(link, &st, &r, &err) != FC_OK)
                break;
            shown = r.generation;
            preview = r.preview;
        }
        if (stop)
            return;
        int ready = 0;
        if (fc_client_wait_input(link->client, REQUEST_POLL_MS, &ready, &err) != FC_OK)
            break;
        if (!ready)
            continue;
        fc_stream_image img;
        if (fc_client_next_image(link->client, &img, &err) != FC_OK)
            break;
        if (img.ended) {
            fc_stream_image_free(&img);
            set_session_state(link, FC_VIEW_SESSION_ENDED);
            if (follow_ended(link, &st, done, have_frame, &err))
                return;
            break;
        }
        if (!have_frame)
            set_session_state(link, FC_VIEW_SESSION_LIVE);
        have_frame = true;
        bool drawn;
        bool ok = show_stream_image(link, &st, &img, shown, preview, &drawn, &err);
        fc_stream_image_free(&img);
        if (!ok)
            break;
    }
    give_up(link, client_exit(&err), "%s", err.message);
}

static void *worker(void *arg)
{
    fc_view_link *link = arg;
    link_state st = {.loaded = UINT32_MAX};
    fc_error err;
    if (fc_view_decoder_create(&st.decoder, &err) != FC_OK)
        give_up(link, client_exit(&err), "%s", err.message);
    else if (link->config.session)
        run_session(link, &st);
    else
        run_files(link, &st);
    fc_view_decoder_free(st.decoder);
    pthread_mutex_lock(&link->slots->lock);
    link->finished = true;
    pthread_mutex_unlock(&link->slots->lock);
    return NULL;
}

fc_code fc_view_link_start(fc_view_link *link, const fc_view_link_config *config, fc_view_slots *slots,
                           fc_client *client, fc_error *err)
{
    memset(link, 0, sizeof *link);
    link->config = *config;
    link->slots = slots;
    link->client = client;
    if (pthread_create(&link->thread, NULL, worker, link) != 0) {
        fc_frame_free(&link->config.first_frame);
        fc_client_close(client);
        return fc_error_set(err, FC_ERR_NOMEM, "cannot start the network thread");
    }
    link->running = true;
    return FC_OK;
}

static bool finished(fc_view_link *link)
{
    pthread_mutex_lock(&link->slots->lock);
    bool f = link->finished;
    pthread_mutex_unlock(&link->slots->lock);
    return f;
}

bool fc_view_link_stop(fc_view_link *link, int timeout_ms)
{
    if (!link->running)
        return true;
    fc_view_slots_stop(link->slots);
    for (int waited = 0; !finished(link) && waited < timeout_ms; waited += 10)
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
    if (!finished(link)) {
        /* Blocked in a session's wait for the next image: the process's exit ends it. */
        pthread_detach(link->thread);
        link->running = false;
        return false;
    }
    pthread_join(link->thread, NULL);
    fc_client_close(link->client);
    fc_frame_free(&link->config.first_frame);
    link->running = false;
    return true;
}
