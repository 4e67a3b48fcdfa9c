/* spacemouse_camera.c — a view-frame delta applied in world space. */
#include "spacemouse_camera.h"

#include <math.h>

#include "fc_error.h"
#include "fc_frame.h"

typedef struct vec3 {
    double x, y, z;
} vec3;

typedef struct view_basis {
    vec3 right, up, back;         /* view x, y, z in world space (back = towards the viewer) */
} view_basis;

static vec3 v3(const float *p) { return (vec3){p[0], p[1], p[2]}; }
static vec3 add(vec3 a, vec3 b) { return (vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static vec3 sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static vec3 scale(vec3 a, double s) { return (vec3){a.x * s, a.y * s, a.z * s}; }
static double dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double len(vec3 a) { return sqrt(dot(a, a)); }
static vec3 cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static void store(vec3 a, float *p)
{
    p[0] = (float)a.x, p[1] = (float)a.y, p[2] = (float)a.z;
}

static view_basis basis_of(const fc_camera *cam)
{
    vec3 forward = sub(v3(cam->target), v3(cam->eye));
    forward = scale(forward, 1.0 / len(forward));
    vec3 right = cross(forward, v3(cam->up));
    right = scale(right, 1.0 / len(right));
    return (view_basis){right, cross(right, forward), scale(forward, -1.0)};
}

/* A view-frame vector in world space. */
static vec3 to_world(const view_basis *b, const float v[3])
{
    return add(add(scale(b->right, v[0]), scale(b->up, v[1])), scale(b->back, v[2]));
}

/* Rodrigues: v rotated by the axis-angle vector w. */
static vec3 rotate(vec3 v, vec3 w)
{
    double angle = len(w);
    if (angle == 0.0)
        return v;
    vec3 k = scale(w, 1.0 / angle);
    double c = cos(angle), s = sin(angle);
    return add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1.0 - c)));
}

/* The scene turns by w about the target: the camera turns by -w about it. */
static void orbit(const fc_sm_camera_delta *d, const view_basis *b, fc_camera *cam)
{
    vec3 target = v3(cam->target), offset = sub(v3(cam->eye), target);
    double distance = len(offset);
    vec3 turn = scale(to_world(b, d->rotate), -1.0);
    offset = scale(rotate(offset, turn), exp(-(double)d->translate[2]));
    const float pan[3] = {d->translate[0], d->translate[1], 0.0f};
    vec3 shift = scale(to_world(b, pan), -distance);
    target = add(target, shift);
    store(target, cam->target);
    store(add(target, offset), cam->eye);
    store(rotate(v3(cam->up), turn), cam->up);
}

/* The camera moves and turns with the puck, about its own eye. */
static void fly(const fc_sm_camera_delta *d, const view_basis *b, fc_camera *cam)
{
    vec3 eye = v3(cam->eye), ahead = sub(v3(cam->target), eye);
    vec3 turn = to_world(b, d->rotate);
    eye = add(eye, scale(to_world(b, d->translate), len(ahead)));
    store(eye, cam->eye);
    store(add(eye, rotate(ahead, turn)), cam->target);
    store(rotate(v3(cam->up), turn), cam->up);
}

fc_code fc_sm_camera_apply(const fc_sm_camera_delta *d, fc_camera *cam, fc_error *err)
{
    fc_code code = fc_camera_validate(cam, err);
    if (code != FC_OK)
        return code;
    view_basis b = basis_of(cam);
    if (d->mode == FC_SM_MODE_FLY)
        fly(d, &b, cam);
    else
        orbit(d, &b, cam);
    return FC_OK;
}
