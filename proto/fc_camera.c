/* fc_camera.c — checking cameras and framing a frame's bounding box. */
#include "fc_frame.h"

#include <math.h>

#include "fc_error.h"

#define FRAMING_FOV_Y_DEG 40.0
#define DEG_TO_RAD (3.14159265358979323846 / 180.0)
/* Below this |sin| between view direction and up, the camera's roll is undefined. */
#define MIN_UP_SINE 1e-6

static double length3(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static bool all_finite(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

fc_code fc_camera_validate(const fc_camera *cam, fc_error *err)
{
    if (!all_finite(cam->eye, 3) || !all_finite(cam->target, 3) || !all_finite(cam->up, 3))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "camera eye, target and up must be finite");
    if (!(cam->fov_y_deg > 0.0f && cam->fov_y_deg < 180.0f))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "camera fov_y_deg %g is outside (0, 180)",
                            (double)cam->fov_y_deg);
    if (cam->width < 1 || cam->height < 1)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "camera image size %ux%u must be at least 1x1",
                            cam->width, cam->height);
    double view[3], up[3], side[3];
    for (int k = 0; k < 3; k++) {
        view[k] = (double)cam->target[k] - cam->eye[k];
        up[k] = cam->up[k];
    }
    double view_len = length3(view), up_len = length3(up);
    if (view_len == 0)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "camera eye and target coincide");
    cross3(view, up, side);
    if (up_len == 0 || length3(side) <= MIN_UP_SINE * view_len * up_len)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "camera up is zero or parallel to the view direction");
    return FC_OK;
}

void fc_camera_frame_bounds(const fc_frame *frame, uint32_t width, uint32_t height, fc_camera *cam)
{
    double centre[3] = {0, 0, 0}, radius = 0, centre_magnitude = 0;
    if (frame->count > 0) {
        float lo[3], hi[3];
        fc_frame_bounds(frame, lo, hi);
        double diagonal[3];
        for (int k = 0; k < 3; k++) {
            centre[k] = 0.5 * ((double)lo[k] + hi[k]);
            diagonal[k] = (double)hi[k] - lo[k];
            centre_magnitude = fmax(centre_magnitude, fabs(centre[k]));
        }
        radius = 0.5 * length3(diagonal);
    }
    if (radius == 0)
        radius = 1.0; /* a single point: any distance shows it; a unit one is as good as any */

    double half_fov_y = 0.5 * FRAMING_FOV_Y_DEG * DEG_TO_RAD;
    double aspect = width && height ? (double)width / height : 1.0;
    double half_fov_x = atan(tan(half_fov_y) * aspect);
    /* The bounding sphere touches the narrower of the two view cones. */
    double distance = radius / sin(fmin(half_fov_x, half_fov_y));
    /* Far from the origin, float rounding could otherwise merge eye and target. */
    distance = fmax(distance, 1e-4 * centre_magnitude);

    const double direction[3] = {-1.0, 1.4, -0.9};
    double direction_len = length3(direction);
    for (int k = 0; k < 3; k++) {
        cam->target[k] = (float)centre[k];
        cam->eye[k] = (float)(centre[k] - direction[k] / direction_len * distance);
        cam->up[k] = k == 2 ? 1.0f : 0.0f;
    }
    cam->fov_y_deg = (float)FRAMING_FOV_Y_DEG;
    cam->width = width;
    cam->height = height;
}
