/* environment.c — sky, floor and light of a render. */
#include "environment.h"

#include <epoxy/gl.h>
#include <math.h>

#include "shader_program.h"
#include "shader_variants.h"
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
    LOC_HAS_FLOOR = 27,
    LOC_EXPOSURE_SCALE = 28,
    LOC_TONE_MAP = 29,
    LOC_SUN_SHADOW = 32,
    LOC_HAS_SHADOW = 36,
    LOC_SHADOW_EXTINCTION = 37,
    LOC_SHADOW_UV_SCALE = 38,
    LOC_HAS_MESH_SHADOW = 39,
    LOC_SHADOW_UV_LAST = 40,
    LOC_SUN_DEPTH_UV_SCALE = 48,
    LOC_MESH_SHADOW_BIAS = 49
};
/* layout(binding) in environment.frag.glsl */
enum { UNIT_SHADOW_MAP = 5, UNIT_FLUID_SUN_DEPTH = 6, UNIT_MESH_SUN_DEPTH = 7 };

/* The sun stands this high over the floor, and (seen from above) this far
 * round from straight behind the camera towards its right: the surfaces the
 * camera sees are lit, highlights fall on them, and the fluid's shadow falls
 * to the left, beside it rather than hidden behind it. */
#define SUN_ELEVATION_DEG 35.0f
#define SUN_AZIMUTH_FROM_BEHIND_DEG 65.0f
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

/* The direction towards the sun in world space, placed relative to where the
 * camera looks (SUN_* above): the camera's backward and right directions
 * projected onto the floor plane. */
static void place_sun(const fc_camera *cam, const float up[3], float sun[3])
{
    float back[3] = {cam->eye[0] - cam->target[0], cam->eye[1] - cam->target[1], cam->eye[2] - cam->target[2]};
    float along_up = fc_dot3(back, up);
    for (int i = 0; i < 3; i++)
        back[i] -= along_up * up[i];
    if (fc_dot3(back, back) < 1e-12f * (1.0f + along_up * along_up)) {
        /* Looking straight down or up: "behind" is the camera's own down direction. */
        float any[3] = {fabsf(up[0]) < 0.9f ? 1.0f : 0.0f, fabsf(up[0]) < 0.9f ? 0.0f : 1.0f, 0.0f};
        fc_cross3(up, any, back);
    }
    fc_normalize3(back);
    float right[3];
    fc_cross3(up, back, right);   /* up x backward = the camera's right */
    const float deg = 3.14159265f / 180.0f;
    float azimuth = SUN_AZIMUTH_FROM_BEHIND_DEG * deg, elevation = SUN_ELEVATION_DEG * deg;
    for (int i = 0; i < 3; i++)
        sun[i] = cosf(elevation) * (cosf(azimuth) * back[i] + sinf(azimuth) * right[i]) + sinf(elevation) * up[i];
    fc_normalize3(sun);
}

/* A world direction in view space: the view matrix's rotation applied. */
static void direction_to_view(const fc_view *view, const float world[3], float out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = view->view[0 * 4 + r] * world[0] + view->view[1 * 4 + r] * world[1] + view->view[2 * 4 + r] * world[2];
    fc_normalize3(out);
}

void fc_environment_for_view(const fc_view *view, const fc_camera *cam, const float lo[3], const float hi[3],
                             const fc_settings *settings, bool has_floor, bool want_u8, fc_environment *env)
{
    const float radius = settings->radius;
    for (int i = 0; i < 3; i++)
        env->up[i] = cam->up[i];
    fc_normalize3(env->up);
    place_sun(cam, env->up, env->sun);
    direction_to_view(view, env->sun, env->light_view);
    env->exposure_scale = exp2f(settings->exposure);
    env->tone_map = want_u8;
    env->has_shadow = false;   /* until shadow_pass.c lays one down */
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

unsigned fc_environment_features(const fc_environment *env)
{
    unsigned features = 0;
    if (env->has_floor)
        features |= FC_FEATURE_FLOOR;
    if (env->has_shadow)
        features |= FC_FEATURE_SHADOW;
    if (env->has_shadow && env->has_mesh_shadow)
        features |= FC_FEATURE_MESH_SHADOW;
    return features;
}

void fc_environment_apply(const fc_environment *env, const fc_view *view)
{
    fc_environment_apply_to(env, view, FC_ALL_UNIFORMS);
}

/* Each setter only where the program has the uniform (fc_uniform_active). */
#define ACTIVE(location) fc_uniform_active(uniforms, location)

static void apply_camera(const fc_view *view, uint64_t uniforms)
{
    if (ACTIVE(LOC_FOCAL))
        glUniform2f(LOC_FOCAL, view->fx, view->fy);
    if (ACTIVE(LOC_VIEW_TO_WORLD))
        glUniformMatrix3fv(LOC_VIEW_TO_WORLD, 1, GL_FALSE, view->view_to_world);
    if (ACTIVE(LOC_EYE_WORLD))
        glUniform3fv(LOC_EYE_WORLD, 1, view->eye);
    if (ACTIVE(LOC_VIEWPORT))
        glUniform2f(LOC_VIEWPORT, (float)view->width, (float)view->height);
}

static void apply_scene(const fc_environment *env, uint64_t uniforms)
{
    if (ACTIVE(LOC_WORLD_UP))
        glUniform3fv(LOC_WORLD_UP, 1, env->up);
    if (ACTIVE(LOC_SUN_DIRECTION))
        glUniform3fv(LOC_SUN_DIRECTION, 1, env->sun);
    if (ACTIVE(LOC_FLOOR_AXIS_U))
        glUniform3fv(LOC_FLOOR_AXIS_U, 1, env->floor_u);
    if (ACTIVE(LOC_FLOOR_AXIS_V))
        glUniform3fv(LOC_FLOOR_AXIS_V, 1, env->floor_v);
    if (ACTIVE(LOC_FLOOR_HEIGHT))
        glUniform1f(LOC_FLOOR_HEIGHT, env->floor_height);
    if (ACTIVE(LOC_CHECKER_SIZE))
        glUniform1f(LOC_CHECKER_SIZE, env->checker_size);
    if (ACTIVE(LOC_PIXEL_ANGLE))
        glUniform1f(LOC_PIXEL_ANGLE, env->pixel_angle);
    if (ACTIVE(LOC_HAS_FLOOR))
        glUniform1i(LOC_HAS_FLOOR, env->has_floor);
    if (ACTIVE(LOC_EXPOSURE_SCALE))
        glUniform1f(LOC_EXPOSURE_SCALE, env->exposure_scale);
    if (ACTIVE(LOC_TONE_MAP))
        glUniform1i(LOC_TONE_MAP, env->tone_map);
}

static void apply_shadows(const fc_environment *env, uint64_t uniforms)
{
    if (ACTIVE(LOC_HAS_SHADOW))
        glUniform1i(LOC_HAS_SHADOW, env->has_shadow);
    if (env->has_shadow) {
        if (ACTIVE(LOC_SUN_SHADOW))
            glUniformMatrix4fv(LOC_SUN_SHADOW, 1, GL_FALSE, env->shadow_transform);
        if (ACTIVE(LOC_SHADOW_EXTINCTION))
            glUniform3fv(LOC_SHADOW_EXTINCTION, 1, env->shadow_extinction);
        if (ACTIVE(LOC_SHADOW_UV_SCALE))
            glUniform2fv(LOC_SHADOW_UV_SCALE, 1, env->shadow_uv_scale);
        if (ACTIVE(LOC_SHADOW_UV_LAST))
            glUniform2fv(LOC_SHADOW_UV_LAST, 1, env->shadow_uv_last);
        glBindTextureUnit(UNIT_SHADOW_MAP, env->shadow_map);
        glBindTextureUnit(UNIT_FLUID_SUN_DEPTH, env->fluid_sun_depth);
    }
    if (ACTIVE(LOC_HAS_MESH_SHADOW))
        glUniform1i(LOC_HAS_MESH_SHADOW, env->has_shadow && env->has_mesh_shadow);
    if (ACTIVE(LOC_SUN_DEPTH_UV_SCALE))
        glUniform4f(LOC_SUN_DEPTH_UV_SCALE, env->fluid_sun_depth_uv_scale[0], env->fluid_sun_depth_uv_scale[1],
                    env->mesh_sun_depth_uv_scale[0], env->mesh_sun_depth_uv_scale[1]);
    if (ACTIVE(LOC_MESH_SHADOW_BIAS))
        glUniform1f(LOC_MESH_SHADOW_BIAS, env->mesh_shadow_bias);
    if (env->has_shadow && env->has_mesh_shadow)
        glBindTextureUnit(UNIT_MESH_SUN_DEPTH, env->mesh_sun_depth);
}

void fc_environment_apply_to(const fc_environment *env, const fc_view *view, uint64_t uniforms)
{
    apply_camera(view, uniforms);
    apply_scene(env, uniforms);
    apply_shadows(env, uniforms);
}
