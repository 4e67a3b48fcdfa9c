/* test_background_regions.c — the background pass's regions (background_regions.h)
 * for several cameras: every pixel centre is drawn by some region; a region
 * drawn with the sky-only variant holds only pixels whose ray the shaders
 * send to the sky, one with the floor-only variant only pixels whose ray
 * meets the floor (environment.frag.glsl's test, computed here as the shader
 * does), and one without the shadow's lookup only floor points whose sun ray
 * misses the shadow casters' box. A region that broke one of these would
 * leave a pixel stale or shade it with the wrong variant. Geometry only: no
 * GL context. */
#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "background_regions.h"
#include "environment.h"
#include "shader_variants.h"
#include "test_util.h"
#include "vec3.h"
#include "view.h"

#define WIDTH 160
#define HEIGHT 120

typedef struct scene {
    const char *name;
    float eye[3], target[3], up[3];
} scene;

/* The particles' box (a pool with a drop above, z up) and the shadow's casters. */
static const float LO[3] = {0.0f, 0.0f, 0.0f}, HI[3] = {1.0f, 1.0f, 0.6f};
static const float RADIUS = 0.01f;

static void make_environment(const scene *s, fc_view *view, fc_environment *env)
{
    fc_camera cam = {.fov_y_deg = 40.0f, .width = WIDTH, .height = HEIGHT};
    memcpy(cam.eye, s->eye, sizeof cam.eye);
    memcpy(cam.target, s->target, sizeof cam.target);
    memcpy(cam.up, s->up, sizeof cam.up);
    fc_view_from_camera(&cam, LO, HI, RADIUS, view);
    fc_settings settings = {.radius = RADIUS};
    fc_environment_for_view(view, &cam, LO, HI, &settings, true, true, env);
    env->has_shadow = true;
    for (int i = 0; i < 3; i++) {
        env->shadow_box_lo[i] = LO[i] - 0.05f;
        env->shadow_box_hi[i] = HI[i] + 0.05f;
    }
}

/* The ray through a pixel centre in world space, unit, as background.frag.glsl. */
static void pixel_ray(const fc_view *view, float x, float y, float dir[3])
{
    float ndc[2] = {x / (float)WIDTH * 2.0f - 1.0f, y / (float)HEIGHT * 2.0f - 1.0f};
    float ray[3] = {ndc[0] / view->fx, ndc[1] / view->fy, -1.0f};
    fc_view_direction_to_world(view, ray, dir);
    fc_normalize3(dir);
}

/* environment.frag.glsl's scene_radiance: whether the ray meets the floor. */
static bool sees_floor(const fc_environment *env, const float eye[3], const float dir[3])
{
    float height = fc_dot3(eye, env->up) - env->floor_height;
    return height > 0.0f && -fc_dot3(dir, env->up) > 0.0f;
}

/* Whether the line through p along the sun meets the box. */
static bool sun_line_meets_box(const fc_environment *env, const float p[3])
{
    double k_lo = -INFINITY, k_hi = INFINITY;
    for (int i = 0; i < 3; i++) {
        double s = env->sun[i], lo = env->shadow_box_lo[i] - p[i], hi = env->shadow_box_hi[i] - p[i];
        if (fabs(s) < 1e-12) {
            if (lo > 0.0 || hi < 0.0)
                return false;
            continue;
        }
        double a = lo / s, b = hi / s;
        k_lo = fmax(k_lo, fmin(a, b));
        k_hi = fmin(k_hi, fmax(a, b));
    }
    return k_lo <= k_hi;
}

static bool draws_pixel(const fc_background_draw *d, float x, float y)
{
    float ndc[2] = {x / (float)WIDTH * 2.0f - 1.0f, y / (float)HEIGHT * 2.0f - 1.0f};
    for (int i = 0; i < 2; i++)
        if (d->clip_planes[i][0] * ndc[0] + d->clip_planes[i][1] * ndc[1] + d->clip_planes[i][2] < 0.0f)
            return false;
    if (!d->scissored)
        return true;
    return x >= (float)d->scissor[0] && x < (float)(d->scissor[0] + d->scissor[2]) && y >= (float)d->scissor[1] &&
           y < (float)(d->scissor[1] + d->scissor[3]);
}

static void check_scene(const scene *s, unsigned features, int *floor_only_pixels, int *sky_only_pixels,
                        int *unshadowed_pixels)
{
    fc_view view;
    fc_environment env;
    make_environment(s, &view, &env);
    fc_background_draw draws[FC_BACKGROUND_DRAWS_MAX];
    int n = fc_background_regions(&view, &env, features, draws);
    CHECK_MSG(n >= 1 && n <= FC_BACKGROUND_DRAWS_MAX, "%s: %d draws", s->name, n);
    int uncovered = 0, wrong_sky = 0, wrong_floor = 0, wrong_shadow = 0;
    for (int py = 0; py < HEIGHT; py++) {
        for (int px = 0; px < WIDTH; px++) {
            float x = (float)px + 0.5f, y = (float)py + 0.5f, dir[3];
            pixel_ray(&view, x, y, dir);
            bool floor = sees_floor(&env, view.eye, dir), covered = false;
            for (int i = 0; i < n; i++) {
                if (!draws_pixel(&draws[i], x, y))
                    continue;
                covered = true;
                unsigned f = draws[i].features;
                if (!(f & FC_FEATURE_FLOOR)) {
                    wrong_sky += floor;
                    ++*sky_only_pixels;
                }
                if (f & FC_FEATURE_FLOOR_ONLY) {
                    wrong_floor += !floor;
                    ++*floor_only_pixels;
                }
                if ((features & FC_FEATURE_SHADOW) && (f & FC_FEATURE_FLOOR_ONLY) && !(f & FC_FEATURE_SHADOW) &&
                    floor) {
                    float along = (env.floor_height - fc_dot3(view.eye, env.up)) / fc_dot3(dir, env.up);
                    float hit[3];
                    for (int k = 0; k < 3; k++)
                        hit[k] = view.eye[k] + along * dir[k];
                    wrong_shadow += sun_line_meets_box(&env, hit);
                    ++*unshadowed_pixels;
                }
            }
            uncovered += !covered;
        }
    }
    CHECK_MSG(uncovered == 0, "%s: %d pixels drawn by no region", s->name, uncovered);
    CHECK_MSG(wrong_sky == 0, "%s: %d floor pixels drawn as sky only", s->name, wrong_sky);
    CHECK_MSG(wrong_floor == 0, "%s: %d sky pixels drawn as floor only", s->name, wrong_floor);
    CHECK_MSG(wrong_shadow == 0, "%s: %d shadowed floor pixels drawn without the shadow", s->name, wrong_shadow);
}

int main(void)
{
    const scene scenes[] = {
        {"from above", {2.0f, -2.9f, 1.9f}, {0.5f, 0.5f, 0.25f}, {0.0f, 0.0f, 1.0f}},
        {"horizon in view", {0.5f, -1.2f, 0.25f}, {0.5f, 0.5f, 0.1f}, {0.0f, 0.0f, 1.0f}},
        {"tilted", {-0.8f, -1.0f, 0.35f}, {0.5f, 0.5f, 0.1f}, {0.3f, 0.0f, 1.0f}},
        {"looking up", {0.5f, -1.0f, 0.05f}, {0.5f, 0.5f, 0.9f}, {0.0f, 0.0f, 1.0f}},
        {"straight down", {0.5f, 0.5f, 3.0f}, {0.5f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}},
        {"below the floor", {0.5f, 0.5f, -0.5f}, {0.5f, 0.5f, 0.1f}, {0.0f, 1.0f, 0.0f}},
        {"close to the floor", {3.0f, 0.5f, 0.02f}, {0.5f, 0.5f, 0.02f}, {0.0f, 0.0f, 1.0f}},
    };
    int floor_only = 0, sky_only = 0, unshadowed = 0;
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        check_scene(&scenes[i], FC_FEATURE_FLOOR | FC_FEATURE_SHADOW, &floor_only, &sky_only, &unshadowed);
        check_scene(&scenes[i], FC_FEATURE_FLOOR, &floor_only, &sky_only, &unshadowed);
        /* Mesh shadows may fall anywhere: no floor region goes without the lookup. */
        int before = unshadowed;
        check_scene(&scenes[i], FC_FEATURE_FLOOR | FC_FEATURE_SHADOW | FC_FEATURE_MESH_SHADOW, &floor_only,
                    &sky_only, &unshadowed);
        CHECK_MSG(unshadowed == before, "%s: a floor region without the mesh shadows' lookup", scenes[i].name);
    }
    /* The cheaper variants are used at all (else the checks above prove nothing). */
    CHECK_MSG(floor_only > 0 && sky_only > 0 && unshadowed > 0, "floor only %d, sky only %d, unshadowed %d pixels",
              floor_only, sky_only, unshadowed);
    /* Without the floor (a client's background) one region, unclipped. */
    fc_view view;
    fc_environment env;
    make_environment(&scenes[1], &view, &env);
    env.has_floor = false;
    fc_background_draw draws[FC_BACKGROUND_DRAWS_MAX];
    CHECK(fc_background_regions(&view, &env, FC_FEATURE_CLIENT_IMAGE, draws) == 1 && !draws[0].scissored);
    return test_result();
}
