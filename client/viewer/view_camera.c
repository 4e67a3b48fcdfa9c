/* view_camera.c — mouse input as fc_sm_camera_delta. */
#include "view_camera.h"

#include <math.h>
#include <string.h>

#include "fc_error.h"

/* A tenth of the eye-target distance per wheel click. */
#define WHEEL_STEP 0.1f

double fc_view_orbit_rad_per_pixel(int window_height)
{
    return M_PI / (window_height > 0 ? window_height : 1);
}

/* Eye-target distances per pixel at the target's depth: what keeps the point
 * under the cursor under it while panning. */
static double pan_per_pixel(const fc_camera *cam, int window_height)
{
    double half = cam->fov_y_deg * M_PI / 360.0;
    return 2.0 * tan(half) / (window_height > 0 ? window_height : 1);
}

fc_sm_camera_delta fc_view_drag_delta(fc_view_drag kind, fc_sm_mode mode, const fc_camera *cam, int dx, int dy,
                                      int window_height)
{
    fc_sm_camera_delta d = {.mode = mode};
    if (kind == FC_VIEW_DRAG_ORBIT) {
        /* Orbit: the scene follows the hand (a drag right turns its front to
         * the right). Fly: the camera looks where the hand goes. */
        float k = (float)fc_view_orbit_rad_per_pixel(window_height) * (mode == FC_SM_MODE_FLY ? -1.0f : 1.0f);
        d.rotate[0] = k * (float)dy;
        d.rotate[1] = k * (float)dx;
        return d;
    }
    /* Pan: the scene moves with the cursor; orbit moves the pivot along (in
     * spacemouse_camera.c the target shifts against translate), fly moves the
     * eye by translate, hence the opposite signs. */
    float s = (float)pan_per_pixel(cam, window_height) * (mode == FC_SM_MODE_FLY ? -1.0f : 1.0f);
    d.translate[0] = s * (float)dx;
    d.translate[1] = -s * (float)dy;
    return d;
}

fc_sm_camera_delta fc_view_wheel_delta(fc_sm_mode mode, float clicks)
{
    fc_sm_camera_delta d = {.mode = mode};
    /* Orbit dollies by exp(-z) towards the pivot; fly moves along view -z. */
    d.translate[2] = (mode == FC_SM_MODE_FLY ? -1.0f : 1.0f) * WHEEL_STEP * clicks;
    return d;
}

static void normalize(double v[3])
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] /= n;
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The camera's up in the view frame (x right, y up, z back), where
 * fc_sm_camera_delta's rotations are expressed. */
static void up_in_view(const fc_camera *cam, double out[3])
{
    double forward[3], up[3], right[3], view_up[3];
    for (int i = 0; i < 3; i++) {
        forward[i] = (double)cam->target[i] - (double)cam->eye[i];
        up[i] = cam->up[i];
    }
    normalize(forward);
    normalize(up);
    cross(forward, up, right);
    normalize(right);
    cross(right, forward, view_up);
    out[0] = dot(up, right);
    out[1] = dot(up, view_up);
    out[2] = -dot(up, forward);
}

/* Cosine of the angle between the view direction and up beyond which the
 * view counts as looking along up (about 2.6 degrees). */
#define ALONG_UP_COS 0.999

fc_code fc_view_turntable(fc_camera *cam, int dx, int dy, int window_height, fc_error *err)
{
    double axis[3];
    up_in_view(cam, axis);
    float k = (float)fc_view_orbit_rad_per_pixel(window_height);
    fc_sm_camera_delta d = {.mode = FC_SM_MODE_ORBIT};
    for (int i = 0; i < 3; i++)
        d.rotate[i] = k * (float)dx * (float)axis[i];
    d.rotate[0] += k * (float)dy;
    fc_camera moved = *cam;
    fc_code code = fc_sm_camera_apply(&d, &moved, err);
    if (code != FC_OK)
        return code;
    memcpy(moved.up, cam->up, sizeof moved.up);
    double forward[3], up[3];
    for (int i = 0; i < 3; i++) {
        forward[i] = (double)moved.target[i] - (double)moved.eye[i];
        up[i] = moved.up[i];
    }
    normalize(forward);
    normalize(up);
    if (fabs(dot(forward, up)) > ALONG_UP_COS)
        return fc_error_set(err, FC_ERR_USAGE, "the view would look along up");
    *cam = moved;
    return FC_OK;
}

bool fc_view_unproject(const fc_camera *cam, float u, float v, float depth, float out[3])
{
    double forward[3], up[3], right[3], view_up[3];
    for (int i = 0; i < 3; i++) {
        forward[i] = (double)cam->target[i] - (double)cam->eye[i];
        up[i] = cam->up[i];
    }
    normalize(forward);
    cross(forward, up, right);
    double n = sqrt(dot(right, right));
    if (!(n > 1e-9) || cam->height == 0)
        return false;
    for (int i = 0; i < 3; i++)
        right[i] /= n;
    cross(right, forward, view_up);
    double half = tan(cam->fov_y_deg * M_PI / 360.0), aspect = (double)cam->width / cam->height;
    double x = (2.0 * u - 1.0) * half * aspect, y = (1.0 - 2.0 * v) * half;
    for (int i = 0; i < 3; i++)
        out[i] = (float)(cam->eye[i] + depth * (forward[i] + x * right[i] + y * view_up[i]));
    return true;
}

void fc_view_set_pivot(fc_camera *cam, const float pivot[3])
{
    for (int i = 0; i < 3; i++) {
        float shift = pivot[i] - cam->target[i];
        cam->eye[i] += shift;
        cam->target[i] = pivot[i];
    }
}
