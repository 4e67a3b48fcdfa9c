/* upright_framing.c — see upright_framing.h. */
#include "upright_framing.h"

#include <math.h>
#include <string.h>

#include "fc_frame.h"

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Rotates x by the shortest rotation taking +z to the unit vector u
 * (Rodrigues: x + v*x + v*(v*x) / (1 + c), v = z cross u, c = z . u); for u
 * = -z, where that rotation is not unique, the half turn about +x. */
static void rotate_z_to(const double u[3], const double x[3], double out[3])
{
    double c = u[2];
    if (c < -1.0 + 1e-9) {
        out[0] = x[0];
        out[1] = -x[1];
        out[2] = -x[2];
        return;
    }
    const double v[3] = {-u[1], u[0], 0.0};
    double vx[3], vvx[3];
    cross(v, x, vx);
    cross(v, vx, vvx);
    for (int k = 0; k < 3; k++)
        out[k] = x[k] + vx[k] + vvx[k] / (1.0 + c);
}

void fc_box_upright(const fc_framing_box *box, uint32_t width, uint32_t height, const float up[3], fc_camera *cam)
{
    float corners[6];
    memcpy(corners, box->lo, sizeof box->lo);
    memcpy(corners + 3, box->hi, sizeof box->hi);
    const fc_frame two_corners = {.count = 2, .positions = corners};
    fc_camera_frame_bounds(&two_corners, width, height, cam);
    double length = sqrt((double)up[0] * up[0] + (double)up[1] * up[1] + (double)up[2] * up[2]);
    memcpy(cam->up, up, sizeof cam->up);
    if (!(length > 0.0))
        return;
    const double u[3] = {up[0] / length, up[1] / length, up[2] / length};
    double offset[3], turned[3];
    for (int k = 0; k < 3; k++)
        offset[k] = (double)cam->eye[k] - cam->target[k];
    rotate_z_to(u, offset, turned);
    for (int k = 0; k < 3; k++)
        cam->eye[k] = (float)(cam->target[k] + turned[k]);
}

fc_code fc_frame_upright(const fc_frame *frame, uint32_t width, uint32_t height, const float up[3], fc_camera *cam,
                         fc_error *err)
{
    fc_framing_box box;
    fc_code code = fc_framing_box_of(frame, &box, err);
    if (code == FC_OK)
        fc_box_upright(&box, width, height, up, cam);
    return code;
}
