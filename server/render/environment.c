/* environment.c — sky, floor and light of a render. */
#include "environment.h"

#include <epoxy/gl.h>
#include <math.h>

#include "vec3.h"

/* Uniform locations fixed by layout(location) in camera.frag.glsl and environment.frag.glsl. */
enum {
    LOC_FOCAL = 0,
    LOC_VIEW_TO_WORLD = 1,
    LOC_EYE_WORLD = 4,
    LOC_VIEWPORT = 5,
    LOC_WORLD_UP = 20,
    LOC_SUN_DIRECTION = 21,
    LOC_FLOOR_AXIS_U = 22,
    LOC_FLOOR_AXIS_V = 23,
    LOC_FLOOR_HEIGHT = 24,
    LOC_CHECKER_SIZE = 25,
    LOC_PIXEL_ANGLE = 26,
    LOC_HAS_FLOOR = 27
};

/* Towards the light in view space: above, left of and behind the camera, so
 * the surfaces the camera sees are lit and the sun shows in reflections. */
static const float LIGHT_VIEW[3] = {-0.35f, 0.75f, 0.56f};
/* Checkers per box diagonal: squares large enough to read through the fluid. */
#define CHECKERS_PER_DIAGONAL 10.0f

/* The world axis least aligned with up, made perpendicular to it: the checker
 * pattern then follows the world axes whenever up is one of them. */
static void floor_axes(const float up[3], float u[3], float v[3])
{
    int axis = 0;
    for (int i = 1; i < 3; i++)
        if (fabsf(up[i]) < fabsf(up[axis]))
            axis = i;
    for (int i = 0; i < 3; i++)
        u[i] = (i == axis ? 1.0f : 0.0f) - up[i] * up[axis];
    fc_normalize3(u);
    fc_cross3(up, u, v);
}

static float lowest_height(const float up[3], const float lo[3], const float hi[3])
{
    float lowest = INFINITY;
    for (int corner = 0; corner < 8; corner++) {
        float c[3];
        for (int i = 0; i < 3; i++)
            c[i] = (corner >> i) & 1 ? hi[i] : lo[i];
        lowest = fminf(lowest, fc_dot3(c, up));
    }
    return lowest;
}

/* The floor as a view-space plane: with x_world = eye + R x_view, the height
 * dot(up, x_world) - floor_height is dot(R^T up, x_view) + dot(up, eye) - floor_height. */
static void floor_plane_in_view(const fc_view *view, fc_environment *env)
{
    if (!env->has_floor) {
        const float none[4] = {0.0f, 0.0f, 0.0f, 1.0f};   /* every point is above it */
        for (int i = 0; i < 4; i++)
            env->floor_plane[i] = none[i];
        return;
    }
    for (int r = 0; r < 3; r++)
        env->floor_plane[r] = view->view[0 * 4 + r] * env->up[0] + view->view[1 * 4 + r] * env->up[1] +
                              view->view[2 * 4 + r] * env->up[2];
    env->floor_plane[3] = fc_dot3(env->up, view->eye) - env->floor_height;
}

void fc_environment_for_view(const fc_view *view, const fc_camera *cam, const float lo[3], const float hi[3],
                             float radius, bool has_floor, fc_environment *env)
{
    for (int i = 0; i < 3; i++) {
        env->up[i] = cam->up[i];
        env->light_view[i] = LIGHT_VIEW[i];
    }
    fc_normalize3(env->up);
    fc_normalize3(env->light_view);
    fc_view_direction_to_world(view, env->light_view, env->sun);
    floor_axes(env->up, env->floor_u, env->floor_v);
    env->floor_height = lowest_height(env->up, lo, hi) - radius;
    env->has_floor = has_floor;
    floor_plane_in_view(view, env);

    float diagonal[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    float size = sqrtf(fc_dot3(diagonal, diagonal)) + 2.0f * radius;
    env->checker_size = size / CHECKERS_PER_DIAGONAL;
    float cx, cy;
    fc_view_pixel_scale(view, &cx, &cy);
    env->pixel_angle = cy;
}

void fc_environment_apply(const fc_environment *env, const fc_view *view)
{
    glUniform2f(LOC_FOCAL, view->fx, view->fy);
    glUniformMatrix3fv(LOC_VIEW_TO_WORLD, 1, GL_FALSE, view->view_to_world);
    glUniform3fv(LOC_EYE_WORLD, 1, view->eye);
    glUniform2f(LOC_VIEWPORT, (float)view->width, (float)view->height);
    glUniform3fv(LOC_WORLD_UP, 1, env->up);
    glUniform3fv(LOC_SUN_DIRECTION, 1, env->sun);
    glUniform3fv(LOC_FLOOR_AXIS_U, 1, env->floor_u);
    glUniform3fv(LOC_FLOOR_AXIS_V, 1, env->floor_v);
    glUniform1f(LOC_FLOOR_HEIGHT, env->floor_height);
    glUniform1f(LOC_CHECKER_SIZE, env->checker_size);
    glUniform1f(LOC_PIXEL_ANGLE, env->pixel_angle);
    glUniform1i(LOC_HAS_FLOOR, env->has_floor);
}
