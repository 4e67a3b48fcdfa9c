/* test_spacemouse_motion.c — filtered axes to a frame's camera delta (the
 * T = (X, -Z, Y), R = (RX, -RZ, RY) convention, dt scaling, signs), the delta
 * applied to an fc_camera in orbit and fly modes, and the button actions. */
#include <math.h>
#include <string.h>

#include "spacemouse_camera.h"
#include "spacemouse_motion.h"
#include "test_util.h"

static float dist3(const float a[3], const float b[3])
{
    return sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static fc_camera front_camera(void)
{
    /* looking down -z from z = 5 at the origin, y up */
    fc_camera cam = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.0f, 640, 480};
    return cam;
}

static void test_convention_and_dt(void)
{
    fc_sm_motion_config c;
    fc_sm_motion_config_default(&c);
    const float axes[6] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
    fc_sm_camera_delta d = fc_sm_motion_delta(&c, axes, FC_SM_MODE_ORBIT, 0.01);
    CHECK(d.mode == FC_SM_MODE_ORBIT);
    CHECK_NEAR(d.translate[0], 0.1 * 0.01, 1e-7);      /* view x =  X */
    CHECK_NEAR(d.translate[1], -0.3 * 0.01, 1e-7);     /* view y = -Z */
    CHECK_NEAR(d.translate[2], 0.2 * 0.01, 1e-7);      /* view z =  Y */
    CHECK_NEAR(d.rotate[0], 0.4 * 1.5707963 * 0.01, 1e-7);
    CHECK_NEAR(d.rotate[1], -0.6 * 1.5707963 * 0.01, 1e-7);
    CHECK_NEAR(d.rotate[2], 0.5 * 1.5707963 * 0.01, 1e-7);
    /* twice the dt, twice the motion */
    fc_sm_camera_delta d2 = fc_sm_motion_delta(&c, axes, FC_SM_MODE_ORBIT, 0.02);
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(d2.translate[k], 2 * d.translate[k], 1e-7);
        CHECK_NEAR(d2.rotate[k], 2 * d.rotate[k], 1e-7);
    }
    /* a stalled frame is capped; no time, no motion */
    fc_sm_camera_delta stall = fc_sm_motion_delta(&c, axes, FC_SM_MODE_FLY, 5.0);
    CHECK_NEAR(stall.translate[0], 0.1 * 0.1, 1e-7);
    fc_sm_camera_delta none = fc_sm_motion_delta(&c, axes, FC_SM_MODE_FLY, 0.0);
    CHECK(none.translate[0] == 0.0f && none.rotate[1] == 0.0f && none.mode == FC_SM_MODE_FLY);
    /* configurable signs */
    c.translate_sign[1] = -1.0f;
    c.rotate_sign[2] = -1.0f;
    fc_sm_camera_delta flipped = fc_sm_motion_delta(&c, axes, FC_SM_MODE_ORBIT, 0.01);
    CHECK_NEAR(flipped.translate[1], -d.translate[1], 1e-7);
    CHECK_NEAR(flipped.rotate[2], -d.rotate[2], 1e-7);
    CHECK_NEAR(flipped.translate[0], d.translate[0], 1e-7);
}

static void test_orbit(void)
{
    fc_error err;
    /* pan: scene right, so the camera moves left by distance * amount */
    fc_camera cam = front_camera();
    fc_sm_camera_delta d = {FC_SM_MODE_ORBIT, {0.1f, 0, 0}, {0, 0, 0}};
    CHECK_CODE(fc_sm_camera_apply(&d, &cam, &err), FC_OK);
    CHECK_NEAR(cam.eye[0], -0.5, 1e-6);
    CHECK_NEAR(cam.target[0], -0.5, 1e-6);
    CHECK_NEAR(cam.eye[2], 5, 1e-6);
    /* dolly: towards the viewer brings the scene closer, multiplicatively */
    cam = front_camera();
    d = (fc_sm_camera_delta){FC_SM_MODE_ORBIT, {0, 0, 0.1f}, {0, 0, 0}};
    fc_sm_camera_apply(&d, &cam, &err);
    CHECK_NEAR(cam.eye[2], 5 * exp(-0.1), 1e-5);
    CHECK_NEAR(cam.target[2], 0, 1e-6);
    /* turn about the view's up: the scene's front moves right, so the camera
     * goes left round the pivot at the same distance, still looking at it */
    cam = front_camera();
    d = (fc_sm_camera_delta){FC_SM_MODE_ORBIT, {0, 0, 0}, {0, 0.3f, 0}};
    fc_sm_camera_apply(&d, &cam, &err);
    CHECK_NEAR(dist3(cam.eye, cam.target), 5, 1e-5);
    CHECK_NEAR(cam.eye[0], -5 * sin(0.3), 1e-5);
    CHECK_NEAR(cam.eye[1], 0, 1e-6);
    CHECK_NEAR(cam.target[0], 0, 1e-6);
    /* turn about the view's x: up turns with the camera */
    cam = front_camera();
    d = (fc_sm_camera_delta){FC_SM_MODE_ORBIT, {0, 0, 0}, {0.2f, 0, 0}};
    fc_sm_camera_apply(&d, &cam, &err);
    CHECK_NEAR(dist3(cam.eye, cam.target), 5, 1e-5);
    float dot_up_view = cam.up[0] * (cam.target[0] - cam.eye[0]) + cam.up[1] * (cam.target[1] - cam.eye[1]) +
                        cam.up[2] * (cam.target[2] - cam.eye[2]);
    CHECK_NEAR(dot_up_view, 0, 1e-5);
    CHECK(fabsf(cam.eye[1]) > 0.5f);
}

static void test_fly(void)
{
    fc_error err;
    /* pushing the puck away (view z negative) flies forward; the target keeps ahead */
    fc_camera cam = front_camera();
    fc_sm_camera_delta d = {FC_SM_MODE_FLY, {0, 0, -0.1f}, {0, 0, 0}};
    fc_sm_camera_apply(&d, &cam, &err);
    CHECK_NEAR(cam.eye[2], 4.5, 1e-6);
    CHECK_NEAR(cam.target[2], -0.5, 1e-6);
    /* turning about up turns the view about the eye, which stays put */
    cam = front_camera();
    d = (fc_sm_camera_delta){FC_SM_MODE_FLY, {0, 0, 0}, {0, 0.25f, 0}};
    fc_sm_camera_apply(&d, &cam, &err);
    CHECK_NEAR(cam.eye[0], 0, 1e-6);
    CHECK_NEAR(cam.eye[2], 5, 1e-6);
    CHECK_NEAR(dist3(cam.eye, cam.target), 5, 1e-5);
    CHECK_NEAR(cam.target[0], -5 * sin(0.25), 1e-5);   /* turned left (counter-clockwise from above) */
    /* a degenerate camera is refused and left alone */
    fc_camera bad = {{1, 1, 1}, {1, 1, 1}, {0, 1, 0}, 45.0f, 64, 64};
    CHECK_CODE(fc_sm_camera_apply(&d, &bad, &err), FC_ERR_INVALID_VALUE);
    CHECK(bad.eye[0] == 1.0f && bad.target[0] == 1.0f);
}

static void test_button_actions(void)
{
    fc_sm_state s;
    fc_sm_state_init(&s);
    fc_sm_decode(&s, (const uint8_t[]){3, 1, 0}, 3);
    fc_sm_actions a = fc_sm_button_actions(&s);
    CHECK(a.reset && !a.toggle_mode);
    fc_sm_decode(&s, (const uint8_t[]){3, 3, 0}, 3);   /* 0 still held, 1 pressed */
    a = fc_sm_button_actions(&s);
    CHECK(!a.reset && a.toggle_mode);
    fc_sm_decode(&s, (const uint8_t[]){3, 3, 0}, 3);   /* held: no new action */
    a = fc_sm_button_actions(&s);
    CHECK(!a.reset && !a.toggle_mode);
    fc_sm_decode(&s, (const uint8_t[]){3, 0, 0}, 3);   /* release: none */
    a = fc_sm_button_actions(&s);
    CHECK(!a.reset && !a.toggle_mode);
    CHECK(fc_sm_mode_toggle(FC_SM_MODE_ORBIT) == FC_SM_MODE_FLY);
    CHECK(fc_sm_mode_toggle(FC_SM_MODE_FLY) == FC_SM_MODE_ORBIT);
}

int main(void)
{
    test_convention_and_dt();
    test_orbit();
    test_fly();
    test_button_actions();
    return test_result();
}
