/* view.c — look-at and perspective for one render. */
#include "view.h"

#include <float.h>
#include <math.h>

#include "vec3.h"

/* Relative margins around the particles' depth range: enough that rounding
 * never clips the nearest or farthest sphere. */
#define DEPTH_MARGIN 1e-3f
/* The near plane never comes closer than this fraction of the far plane, which
 * bounds the depth buffer's range ratio when the camera is among particles. */
#define MIN_NEAR_FRACTION 1e-5f

static const double PI = 3.14159265358979323846;

/* Camera basis: right, true up and forward, orthonormal. */
static void camera_basis(const fc_camera *cam, float right[3], float up[3], float forward[3])
{
    for (int i = 0; i < 3; i++)
        forward[i] = cam->target[i] - cam->eye[i];
    fc_normalize3(forward);
    fc_cross3(forward, cam->up, right);
    fc_normalize3(right);
    fc_cross3(right, forward, up);
}

static void set_view_matrix(fc_view *v, const float right[3], const float up[3], const float forward[3])
{
    const float *rows[3] = {right, up, forward};
    for (int r = 0; r < 3; r++) {
        float sign = r == 2 ? -1.0f : 1.0f;   /* the camera looks down -z */
        for (int c = 0; c < 3; c++)
            v->view[c * 4 + r] = sign * rows[r][c];
        v->view[12 + r] = -sign * fc_dot3(rows[r], v->eye);
        v->view[r * 4 + 3] = 0.0f;
        /* The inverse rotation is the transpose: columns right, up, backward. */
        for (int c = 0; c < 3; c++)
            v->view_to_world[r * 3 + c] = sign * rows[r][c];
    }
    v->view[15] = 1.0f;
}

/* Distances along the view axis of the nearest and farthest corner of [lo, hi] grown by radius. */
static void depth_range(const fc_view *v, const float forward[3], const float lo[3], const float hi[3],
                        float radius, float *nearest, float *farthest)
{
    *nearest = FLT_MAX;
    *farthest = -FLT_MAX;
    for (int corner = 0; corner < 8; corner++) {
        float offset[3];
        for (int i = 0; i < 3; i++) {
            float c = (corner >> i) & 1 ? hi[i] + radius : lo[i] - radius;
            offset[i] = c - v->eye[i];
        }
        float d = fc_dot3(offset, forward);
        *nearest = fminf(*nearest, d);
        *farthest = fmaxf(*farthest, d);
    }
}

static void set_depth_planes(fc_view *v, float nearest, float farthest)
{
    if (farthest <= 0.0f) {
        /* Everything is behind the camera: any valid planes render nothing. */
        farthest = 1.0f;
    }
    v->far_plane = farthest * (1.0f + DEPTH_MARGIN);
    v->near_plane = fmaxf(nearest * (1.0f - DEPTH_MARGIN), v->far_plane * MIN_NEAR_FRACTION);
    float n = v->near_plane, f = v->far_plane;
    v->p22 = -(f + n) / (f - n);
    v->p32 = -2.0f * f * n / (f - n);
}

void fc_view_from_camera(const fc_camera *cam, const float lo[3], const float hi[3], float radius, fc_view *out)
{
    float right[3], up[3], forward[3];
    for (int i = 0; i < 3; i++)
        out->eye[i] = cam->eye[i];
    camera_basis(cam, right, up, forward);
    set_view_matrix(out, right, up, forward);

    out->width = cam->width;
    out->height = cam->height;
    float aspect = (float)cam->width / (float)cam->height;
    out->fy = (float)(1.0 / tan(cam->fov_y_deg * PI / 360.0));
    out->fx = out->fy / aspect;

    float nearest, farthest;
    depth_range(out, forward, lo, hi, radius, &nearest, &farthest);
    set_depth_planes(out, nearest, farthest);
}

void fc_view_pixel_scale(const fc_view *v, float *cx, float *cy)
{
    *cx = 2.0f / ((float)v->width * v->fx);
    *cy = 2.0f / ((float)v->height * v->fy);
}

void fc_view_direction_to_world(const fc_view *v, const float view_dir[3], float world_dir[3])
{
    for (int i = 0; i < 3; i++)
        world_dir[i] = v->view_to_world[0 * 3 + i] * view_dir[0] + v->view_to_world[1 * 3 + i] * view_dir[1] +
                       v->view_to_world[2 * 3 + i] * view_dir[2];
}
