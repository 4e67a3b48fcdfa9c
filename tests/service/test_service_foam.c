/* test_service_foam.c — the foam history through the real fluidcastd: a block
 * of particles whose velocity jumps by more than foam_tau gets more surface
 * noise (the noise AOV, as EXR) in the frame of the jump, and the extra noise
 * decays by foam_decay per following frame, while a calm block keeps its
 * noise. The history belongs to one particle stream: a connection's own
 * FRAMEs, or a named session's frames, shared by all its viewers. However
 * often a frame is rendered, and whatever other streams the GL thread uploads
 * in between, it shows the amplitudes of its own single advance.
 *
 * A particle splats its amplitude times a pattern fixed by its id and its
 * place on screen, so with particles that stay put each block's summed |noise|
 * scales exactly with the block's amplitude: its ratio to the first, calm
 * frame is the amplitude multiplier 1 + raise. */
#include <math.h>
#include <stdio.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "support/image_decode.h"
#include "test_util.h"

enum { WIDTH = 96, HEIGHT = 48, SIDE = 3, FRAMES = 5, VIEWERS = 2 };
#define SPACING 0.1f
#define RADIUS 0.05f
#define BLOCK_X 0.4f   /* block centres: x = -BLOCK_X (left half of the image), +BLOCK_X (right half) */
#define EYE_Z 1.0f
#define TAU 0.5f
#define DECAY 0.5f
#define KICK 2.0f      /* the left block's velocity from its kick on: a jump of 4 tau */
#define DRIFT 0.1f     /* the right block's velocity, the same in every frame */
#define TOLERANCE 1e-4 /* relative: the same splats, each scaled by one float */

/* Indices of the per-block sums. */
enum { KICKED = 0, CALM = 1 };

static const fc_render_request noise_request = {.format = FC_FORMAT_EXR, .quality = 0, .aov = FC_AOV_NOISE};

/* Two SIDE x SIDE blocks of touching particles in the plane z = 0; the left
 * one moves at KICK when `kicked`, else rests; the right one drifts. */
static fc_code make_scene(bool kicked, fc_frame *frame, fc_error *err)
{
    const uint64_t per_block = SIDE * SIDE;
    fc_code code = fc_frame_alloc(frame, 2 * per_block, FC_ATTR_VELOCITY | FC_ATTR_IDS, err);
    if (code != FC_OK)
        return code;
    for (uint64_t i = 0; i < frame->count; i++) {
        bool left = i < per_block;
        uint64_t cell = i % per_block;
        float *p = frame->positions + 3 * i, *v = frame->velocity + 3 * i;
        p[0] = (left ? -BLOCK_X : BLOCK_X) + (float)((int)(cell % SIDE) - SIDE / 2) * SPACING;
        p[1] = (float)((int)(cell / SIDE) - SIDE / 2) * SPACING;
        p[2] = 0.0f;
        v[0] = left ? (kicked ? KICK : 0.0f) : DRIFT;
        v[1] = v[2] = 0.0f;
        frame->ids[i] = (uint32_t)((left ? 100 : 200) + cell);
    }
    return FC_OK;
}

static void foam_settings(float noise, fc_settings *s)
{
    fc_settings_default(s);
    s->radius = RADIUS;
    s->smoothing = FC_SMOOTHING_NONE;
    s->noise = noise;
    s->foam_tau = TAU;
    s->foam_decay = DECAY;
    s->density_threshold = 0.0f;
}

static bool set_noise(fc_client *c, float noise)
{
    fc_settings s;
    fc_error err;
    foam_settings(noise, &s);
    if (fc_client_set_settings(c, &s, &err) == FC_OK)
        return true;
    fprintf(stderr, "settings: %s\n", err.message);
    return false;
}

/* A client looking at both blocks from the +z axis, with noise 1. */
static fc_client *connect_looking(const fc_test_daemon *d, const char *name)
{
    fc_client *c = svc_client(d, name);
    fc_camera cam;
    fc_error err;
    svc_axis_camera(EYE_Z, WIDTH, HEIGHT, &cam);
    if (c && (fc_client_set_camera(c, &cam, &err) != FC_OK || !set_noise(c, 1.0f))) {
        fc_client_close(c);
        return NULL;
    }
    return c;
}

/* Sums |N| over the left (kicked block) and right (calm block) halves of a noise EXR. */
static bool noise_sums(const fc_image_result *image, double sums[2])
{
    fc_decoded_image img;
    fc_error err;
    if (fc_decode_image(image->data, image->size, "exr", 1, &img, &err) != FC_OK) {
        fprintf(stderr, "decoding the noise image: %s\n", err.message);
        return false;
    }
    bool ok = img.width == WIDTH && img.height == HEIGHT && img.channels == 1 && img.as_float;
    const float *pixels = img.pixels;
    sums[KICKED] = sums[CALM] = 0.0;
    for (uint32_t i = 0; ok && i < WIDTH * HEIGHT; i++)
        sums[i % WIDTH < WIDTH / 2 ? KICKED : CALM] += fabs((double)pixels[i]);
    if (!ok)
        fprintf(stderr, "noise image %ux%u, %u channel(s)\n", img.width, img.height, img.channels);
    fc_decoded_image_free(&img);
    return ok;
}

static bool render_noise(fc_client *c, double sums[2])
{
    fc_image_result image = {0};
    fc_error err;
    bool ok = fc_client_render(c, &noise_request, &image, &err) == FC_OK;
    if (!ok)
        fprintf(stderr, "render: %s\n", err.message);
    ok = ok && noise_sums(&image, sums);
    fc_image_result_free(&image);
    return ok;
}

/* Sends the scene as the client's next frame and renders its noise. */
static bool show(fc_client *c, bool kicked, double sums[2])
{
    fc_frame frame = {0};
    fc_error err;
    bool ok = make_scene(kicked, &frame, &err) == FC_OK && fc_client_send_frame(c, &frame, &err) == FC_OK;
    if (!ok)
        fprintf(stderr, "frame: %s\n", err.message);
    fc_frame_free(&frame);
    return ok && render_noise(c, sums);
}

static bool same_noise(const double a[2], const double b[2])
{
    return fabs(a[KICKED] - b[KICKED]) <= TOLERANCE * b[KICKED] && fabs(a[CALM] - b[CALM]) <= TOLERANCE * b[CALM];
}

/* The raise of the kicked block over its calm noise `first`, checking the calm block kept its own. */
static double raise_over(const double sums[2], const double first[2])
{
    CHECK_NEAR(sums[CALM] / first[CALM], 1.0, TOLERANCE);
    return sums[KICKED] / first[KICKED] - 1.0;
}

/* Frame 2 (the jump) raises the kicked block; each later, unchanged frame takes DECAY of the raise away. */
static void check_raise(int frame, double raise, double previous)
{
    if (frame == 2)
        CHECK_MSG(raise > 0.5, "raise after the jump: %g", raise);
    else
        CHECK_MSG(raise < previous && fabs(raise - DECAY * previous) <= TOLERANCE, "frame %d: raise %g after %g",
                  frame, raise, previous);
}

/* Frames 1..FRAMES of one connection follow the raise and its decay; then a
 * frame first rendered with noise 0 shows none yet advances the history once,
 * and renders of one frame neither advance nor reset it. */
static void test_raise_and_decay(const fc_test_daemon *d)
{
    fc_client *c = connect_looking(d, "foam");
    double first[2], sums[2], again[2], raise = 0.0;
    bool ok = c && show(c, false, first);
    CHECK(ok);
    CHECK_MSG(!ok || (first[KICKED] > 0.0 && first[CALM] > 0.0), "no noise to scale: %g, %g", first[KICKED],
              first[CALM]);
    for (int f = 2; ok && f <= FRAMES; f++) {
        ok = show(c, true, sums);
        CHECK(ok);
        double next = ok ? raise_over(sums, first) : 0.0;
        check_raise(f, next, raise);
        raise = next;
    }
    ok = ok && set_noise(c, 0.0f) && show(c, true, sums);
    CHECK_MSG(ok && sums[KICKED] == 0.0 && sums[CALM] == 0.0, "noise 0: |N| sums %g, %g", sums[KICKED], sums[CALM]);
    ok = ok && set_noise(c, 1.0f) && render_noise(c, sums);
    CHECK(ok);
    if (ok)
        check_raise(FRAMES + 1, raise_over(sums, first), raise);
    CHECK(ok && render_noise(c, again) && same_noise(again, sums));
    fc_client_close(c);
}

/* Two connections with the same particle ids: each has a history of its own,
 * and a frame uploaded again after the other connection's keeps its raise. */
static void test_connections_do_not_leak(const fc_test_daemon *d)
{
    fc_client *a = connect_looking(d, "foam-a"), *b = connect_looking(d, "foam-b");
    double a_calm[2], a_kicked[2], a_again[2], a_next[2], b_first[2], b_second[2];
    /* B starts where A jumps to, and stays there: with a history of its own, B is never raised. */
    bool ok = a && b && show(a, false, a_calm) && show(b, true, b_first) && show(a, true, a_kicked) &&
              show(b, true, b_second);
    CHECK(ok);
    if (!ok) {
        fc_client_close(a);
        fc_client_close(b);
        return;
    }
    CHECK(same_noise(b_first, a_calm) && same_noise(b_second, a_calm));
    double raise = raise_over(a_kicked, a_calm);
    check_raise(2, raise, 0.0);
    /* A's frame goes to the GPU again after B's: its own amplitudes, not B's, and not advanced. */
    CHECK(render_noise(a, a_again) && same_noise(a_again, a_kicked));
    CHECK(show(a, true, a_next));
    check_raise(3, raise_over(a_next, a_calm), raise);
    fc_client_close(a);
    fc_client_close(b);
}

static bool subscribe_all(fc_client *const viewers[VIEWERS])
{
    fc_error err;
    for (int v = 0; v < VIEWERS; v++) {
        if (!viewers[v])
            return false;
        if (fc_client_subscribe(viewers[v], "foam", &noise_request, WIDTH, HEIGHT, NULL, &err) != FC_OK) {
            fprintf(stderr, "viewer %d cannot subscribe: %s\n", v, err.message);
            return false;
        }
    }
    return true;
}

/* Reads a viewer's images until the session ends: each must show exactly the
 * noise the producer's render of the same frame showed. */
static void check_viewer(fc_client *viewer, int index, double shown[FRAMES + 1][2])
{
    uint64_t last_frame = 0;
    int images = 0, wrong = 0;
    bool ended = false, ok = true;
    while (ok && !ended) {
        fc_stream_image img = {0};
        fc_error err;
        double sums[2];
        ok = fc_client_next_image(viewer, &img, &err) == FC_OK;
        if (!ok)
            fprintf(stderr, "viewer %d: %s\n", index, err.message);
        ended = ok && img.ended;
        if (ok && !ended) {
            ok = img.frame_number >= 1 && img.frame_number <= FRAMES && noise_sums(&img.image, sums);
            wrong += ok && !same_noise(sums, shown[img.frame_number]);
            images++;
            last_frame = img.frame_number;
        }
        fc_stream_image_free(&img);
    }
    CHECK_MSG(ok && ended && images >= 1 && wrong == 0 && last_frame == FRAMES,
              "viewer %d: %d image(s), %d with other noise than the producer's, last frame %llu", index, images,
              wrong, (unsigned long long)last_frame);
}

/* A session's frames share one history, advanced once per frame however many
 * viewers and renders show it: the producer's renders follow the raise and
 * its decay, a frame rendered again after another stream's keeps its noise,
 * and every viewer's image of a frame shows the producer's noise of it. */
static void test_session_shares_history(const fc_test_daemon *d)
{
    fc_client *producer = connect_looking(d, "producer"), *other = connect_looking(d, "other");
    fc_client *viewers[VIEWERS] = {connect_looking(d, "viewer-1"), connect_looking(d, "viewer-2")};
    fc_error err;
    bool ok = producer && other && fc_client_publish(producer, "foam", NULL, &err) == FC_OK && subscribe_all(viewers);
    double shown[FRAMES + 1][2], raise = 0.0;
    for (int f = 1; ok && f <= FRAMES; f++) {
        double again[2], others[2];
        ok = show(producer, f >= 2, shown[f]) && show(other, true, others) && render_noise(producer, again);
        if (!ok)
            break;
        CHECK_MSG(same_noise(again, shown[f]), "frame %d rendered again after another stream's", f);
        /* The other connection's history is its own: its unchanged frames stay calm. */
        CHECK_MSG(same_noise(others, shown[1]), "the other connection's frame %d", f);
        if (f >= 2) {
            double next = raise_over(shown[f], shown[1]);
            check_raise(f, next, raise);
            raise = next;
        }
    }
    ok = ok && fc_client_leave_session(producer, &err) == FC_OK;
    CHECK(ok);
    for (int v = 0; ok && v < VIEWERS; v++)
        check_viewer(viewers[v], v, shown);
    for (int v = 0; v < VIEWERS; v++)
        fc_client_close(viewers[v]);
    fc_client_close(other);
    fc_client_close(producer);
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, NULL);
    test_raise_and_decay(&daemon);
    test_connections_do_not_leak(&daemon);
    test_session_shares_history(&daemon);
    CHECK(svc_stop_daemon(&daemon));
    return test_result();
}
