/* test_service_session_end.c — sessions that end keep their last frame for the
 * viewers still in them (PROTOCOL.md 10.1), against the real fluidcastd:
 *   - a viewer that subscribes before any producer is told it waits (producers
 *     0, last frame 0), then gets the first frame's image;
 *   - after the last producer leaves, the viewer gets SESSION_END (`ended`)
 *     and stays: its CAMERA still re-renders the last frame, a new image that
 *     differs from the one before (the depth at the centre moves with the eye);
 *   - the ended session is not listed, and a new PUBLISH of its name is a new
 *     session: the ended viewer does not see the new run's frames and still
 *     orbits the old last frame, until it subscribes again (which leaves the
 *     ended session) and then gets the new run's frame;
 *   - the ended session counts against --max-sessions (2 here) while it has a
 *     viewer and is freed when its last viewer leaves. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_util.h"

enum { SIZE = 41 };

static const fc_render_request depth = {.format = FC_FORMAT_RAW, .aov = FC_AOV_DEPTH};

static bool push_frame(fc_client *c, float dz)
{
    fc_frame f = {0};
    fc_error err;
    bool ok = svc_grid_frame(dz, &f, &err) == FC_OK && fc_client_send_frame(c, &f, &err) == FC_OK;
    if (!ok)
        fprintf(stderr, "push frame: %s\n", err.message);
    fc_frame_free(&f);
    return ok;
}

/* A viewer with the axis camera at eye_z, subscribed to `session`. */
static fc_client *viewer(const fc_test_daemon *d, const char *session, float eye_z, fc_session_status *status)
{
    fc_client *v = svc_client(d, "viewer");
    fc_camera cam;
    fc_settings settings;
    svc_axis_camera(eye_z, SIZE, SIZE, &cam);
    svc_settings(&settings);
    fc_error err;
    bool ok = v && fc_client_set_camera(v, &cam, &err) == FC_OK && fc_client_set_settings(v, &settings, &err) == FC_OK &&
              fc_client_subscribe(v, session, &depth, SIZE, SIZE, status, &err) == FC_OK;
    CHECK_MSG(ok, "viewer of %s: %s", session, v ? err.message : "no connection");
    return v;
}

static bool move_camera(fc_client *v, float eye_z)
{
    fc_camera cam;
    fc_error err;
    svc_axis_camera(eye_z, SIZE, SIZE, &cam);
    return fc_client_set_camera(v, &cam, &err) == FC_OK;
}

/* The viewer's next image, which must be one (not the end); its centre depth in *centre. */
static bool next_image(fc_client *v, fc_stream_image *img, float *centre)
{
    fc_error err;
    if (fc_client_next_image(v, img, &err) != FC_OK) {
        fprintf(stderr, "next image: %s\n", err.message);
        return false;
    }
    if (img->ended || img->image.format != FC_FORMAT_RAW) {
        fprintf(stderr, "expected a RAW image, got ended %d format %d\n", img->ended, (int)img->image.format);
        return false;
    }
    *centre = svc_raw_centre(&img->image);
    return true;
}

static uint32_t listed_sessions(fc_client *c)
{
    fc_session_status *list = NULL;
    uint32_t count = UINT32_MAX;
    fc_error err;
    if (fc_client_list_sessions(c, &list, &count, &err) != FC_OK)
        fprintf(stderr, "list sessions: %s\n", err.message);
    fc_session_list_free(list);
    return count;
}

/* A client publishing `name`, trying a bounded number of times while the
 * daemon is at --max-sessions (it frees a closed connection's session soon
 * after the close); NULL when it never fits. */
static fc_client *publish_when_it_fits(const fc_test_daemon *d, const char *name)
{
    fc_client *c = svc_client(d, "producer");
    fc_error err;
    fc_code code = FC_ERR_LIMIT;
    for (int tries = 0; c && code == FC_ERR_LIMIT && tries < 100; tries++) {
        code = fc_client_publish(c, name, NULL, &err);
        if (code == FC_ERR_LIMIT)
            svc_sleep_ms(20);
    }
    if (code == FC_OK)
        return c;
    fprintf(stderr, "publish %s: %s\n", name, err.message);
    fc_client_close(c);
    return NULL;
}

static fc_code publish(const fc_test_daemon *d, const char *name, fc_client **out)
{
    fc_error err;
    *out = svc_client(d, "producer");
    return *out ? fc_client_publish(*out, name, NULL, &err) : FC_ERR_IO;
}

int main(void)
{
    const char *const args[] = {"--max-image", "256x256", "--max-sessions", "2", NULL};
    fc_test_daemon d;
    svc_start_daemon(&d, args);
    fc_stream_image img;
    fc_error err;
    float centre = 0.0f;

    /* Waiting: subscribed before any producer. */
    fc_session_status status;
    fc_client *v = viewer(&d, "run", 3.0f, &status);
    CHECK_MSG(status.producers == 0 && status.last_frame == 0 && status.frames == 0, "waiting: %u producers, frame %llu",
              status.producers, (unsigned long long)status.last_frame);
    CHECK(!fc_client_session_ended(v));
    fc_client *p;
    CHECK_CODE(publish(&d, "run", &p), FC_OK);
    CHECK(push_frame(p, 0.0f));
    CHECK(next_image(v, &img, &centre));
    CHECK(img.frame_number == 1 && !img.view_change);
    CHECK_NEAR(centre, svc_axis_depth(3.0f, 0.0f), 0.01);
    fc_stream_image_free(&img);

    /* The producer leaves: the viewer is told, and stays. */
    CHECK_CODE(fc_client_leave_session(p, &err), FC_OK);
    CHECK_CODE(fc_client_next_image(v, &img, &err), FC_OK);
    CHECK(img.ended && img.image.data == NULL);
    fc_stream_image_free(&img);
    CHECK(fc_client_session_ended(v));
    CHECK_MSG(listed_sessions(p) == 0, "an ended session is listed");

    /* Its camera still works: the last frame again, seen from further away. */
    float before = centre;
    CHECK(move_camera(v, 4.5f));
    CHECK(next_image(v, &img, &centre));
    CHECK(img.view_change && img.frame_number == 1 && img.missed == 0);
    CHECK_NEAR(centre, svc_axis_depth(4.5f, 0.0f), 0.01);
    CHECK_MSG(fabsf(centre - before) > 1.0f, "the picture did not change: depth %g then %g", before, centre);
    fc_stream_image_free(&img);
    /* RENDER on it renders the ended session's frame too. */
    fc_image_result render = {0};
    CHECK_CODE(fc_client_render(v, &depth, &render, &err), FC_OK);
    CHECK_NEAR(svc_raw_centre(&render), svc_axis_depth(4.5f, 0.0f), 0.01);
    fc_image_result_free(&render);

    /* --max-sessions 2: the ended session with its viewer holds one place. */
    fc_client *elsewhere, *third;
    CHECK_CODE(publish(&d, "elsewhere", &elsewhere), FC_OK);
    CHECK_CODE(publish(&d, "third", &third), FC_ERR_LIMIT);
    fc_client_close(third);

    /* Subscribing again leaves the ended session, which is freed with its last
     * viewer gone: the name opens a new session in the place it held. */
    CHECK_CODE(fc_client_subscribe(v, "run", &depth, SIZE, SIZE, &status, &err), FC_OK);
    CHECK_MSG(status.producers == 0 && status.frames == 0 && status.viewers == 1, "new run: %u producers, %llu frames",
              status.producers, (unsigned long long)status.frames);
    CHECK(!fc_client_session_ended(v));
    fc_client *p2;
    CHECK_CODE(publish(&d, "run", &p2), FC_OK);
    CHECK(push_frame(p2, 0.5f));
    CHECK(next_image(v, &img, &centre));
    CHECK(img.frame_number == 1 && img.sequence == 1 && !img.view_change);
    CHECK_NEAR(centre, svc_axis_depth(4.5f, 0.5f), 0.01);
    fc_stream_image_free(&img);
    fc_client *w = viewer(&d, "run", 3.0f, NULL);
    CHECK(next_image(w, &img, &centre));   /* the frame there already */
    fc_stream_image_free(&img);

    /* The second run ends by its producer's disconnect, with two viewers. */
    fc_client_close(p2);
    CHECK(fc_client_next_image(v, &img, &err) == FC_OK && img.ended);
    fc_stream_image_free(&img);
    CHECK(fc_client_next_image(w, &img, &err) == FC_OK && img.ended);
    fc_stream_image_free(&img);

    /* A new PUBLISH of the name while they remain: a new session, which the
     * ended viewers do not see; they still orbit the second run's last frame. */
    fc_client_close(elsewhere);
    fc_client *p3 = publish_when_it_fits(&d, "run");
    CHECK(p3 != NULL && push_frame(p3, 1.0f));
    CHECK(move_camera(v, 3.0f));
    CHECK(next_image(v, &img, &centre));
    CHECK_MSG(img.view_change && img.frame_number == 1, "view %d frame %llu", img.view_change,
              (unsigned long long)img.frame_number);
    CHECK_NEAR(centre, svc_axis_depth(3.0f, 0.5f), 0.01);
    fc_stream_image_free(&img);
    CHECK_CODE(publish(&d, "fourth", &third), FC_ERR_LIMIT);
    fc_client_close(third);

    /* One viewer leaves: the ended session stays for the other. */
    CHECK_CODE(fc_client_leave_session(w, &err), FC_OK);
    CHECK_CODE(fc_client_next_image(w, &img, &err), FC_ERR_USAGE);
    CHECK_CODE(publish(&d, "fourth", &third), FC_ERR_LIMIT);
    fc_client_close(third);
    /* The last one leaves: the daemon frees it. */
    CHECK_CODE(fc_client_leave_session(v, &err), FC_OK);
    CHECK(!fc_client_session_ended(v));
    fc_client *fourth = publish_when_it_fits(&d, "fourth");
    CHECK_MSG(fourth != NULL, "the ended session was not freed after its last viewer left");

    fc_client_close(fourth);
    fc_client_close(p3);
    fc_client_close(w);
    fc_client_close(v);
    fc_client_close(p);
    CHECK(svc_stop_daemon(&d));
    return test_result();
}
