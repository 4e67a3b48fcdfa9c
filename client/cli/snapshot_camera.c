/* snapshot_camera.c — see snapshot_camera.h. */
#include "snapshot_camera.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "upright_framing.h"

#define DEG_TO_RAD 0.017453292519943295

/* Half of the narrower of the two fields of view, in radians: the angle the
 * framed bounding sphere has to fit in. */
static double limiting_half_angle(double fov_y_deg, double aspect)
{
    double half_y = 0.5 * fov_y_deg * DEG_TO_RAD;
    double half_x = atan(tan(half_y) * aspect);
    return half_y < half_x ? half_y : half_x;
}

/* A sphere of radius r fits a cone of half-angle a from distance r / sin(a), so
 * scaling the eye's distance by sin(a_old) / sin(a_new) keeps the framing. */
static void refit_to_fov(fc_camera *cam, float fov_deg)
{
    double aspect = (double)cam->width / (double)cam->height;
    double scale = sin(limiting_half_angle(cam->fov_y_deg, aspect)) / sin(limiting_half_angle(fov_deg, aspect));
    for (int k = 0; k < 3; k++)
        cam->eye[k] = cam->target[k] + (float)((cam->eye[k] - cam->target[k]) * scale);
    cam->fov_y_deg = fov_deg;
}

fc_code fc_snapshot_camera(const fc_snapshot_options *o, const fc_framing_box *box, fc_up_choice *up,
                           fc_camera *cam, fc_error *err)
{
    if (o->has_eye) {
        memcpy(cam->eye, o->eye, sizeof cam->eye);
        memcpy(cam->target, o->target, sizeof cam->target);
        cam->fov_y_deg = o->fov_deg;
        cam->width = o->width;
        cam->height = o->height;
        fc_up_choice_fit_view(up, o->eye, o->target);
        memcpy(cam->up, up->up, sizeof cam->up);
    } else {
        fc_box_upright(box, o->width, o->height, up->up, cam);
        if (o->has_fov)
            refit_to_fov(cam, o->fov_deg);
    }
    fc_error why;
    if (fc_camera_validate(cam, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_USAGE, "bad camera: %s", why.message);
    return FC_OK;
}

void fc_snapshot_print_left_out(const fc_framing_box *box, bool sequence)
{
    if (box->left_out == 0)
        return;
    printf("framing: the fluid without %s%llu particle%s%s far from it (--eye/--target to frame them)\n",
           sequence ? "up to " : "", (unsigned long long)box->left_out, box->left_out == 1 ? "" : "s",
           sequence ? " a frame" : "");
}
