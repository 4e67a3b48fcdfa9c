/* background_regions.c — see background_regions.h. */
#include "background_regions.h"

#include <math.h>

#include "shader_variants.h"
#include "vec3.h"

/* Pixels from the horizon line beyond which the sky's and the floor's own
 * programs draw, and the half-width of the general program's band: rounding
 * moves the shaders' test by far less than a pixel. */
#define REGION_MARGIN_PX 1.0f
#define BAND_HALF_WIDTH_PX 2.0f
/* Pixels added around the shadow's rectangle. */
#define SHADOW_RECT_MARGIN_PX 2

static const float keep_all[3] = {0.0f, 0.0f, 1.0f};

static void set_plane(float plane[3], float a, float b, float c)
{
    plane[0] = a;
    plane[1] = b;
    plane[2] = c;
}

static fc_background_draw unclipped(unsigned features)
{
    fc_background_draw d = {.features = features};
    for (int i = 0; i < 2; i++)
        set_plane(d.clip_planes[i], keep_all[0], keep_all[1], keep_all[2]);
    return d;
}

/* The ray through NDC (x, y) meets the floor where dot(floor_plane.xyz,
 * (x / fx, y / fy, -1)) < 0 (fluid_pixel.frag.glsl, with the eye above the
 * floor): a x + b y + c < 0. *per_pixel: how much the line's value changes
 * per pixel across it. False without a horizon line to split at. */
static bool horizon_line(const fc_view *view, const fc_environment *env, float line[3], float *per_pixel)
{
    const float *fp = env->floor_plane;
    if (!env->has_floor || !(fp[3] > 0.0f))
        return false;
    set_plane(line, fp[0] / view->fx, fp[1] / view->fy, -fp[2]);
    float gx = line[0] * 2.0f / (float)view->width, gy = line[1] * 2.0f / (float)view->height;
    *per_pixel = sqrtf(gx * gx + gy * gy);
    return *per_pixel > 0.0f && isfinite(*per_pixel);
}

/* The world point p in pixels; false when it is not in front of the camera. */
static bool to_pixels(const fc_view *view, const float p[3], float px[2])
{
    const float *m = view->view;
    float x = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12];
    float y = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
    float depth = -(m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]);
    if (!(depth > 0.5f * view->near_plane))
        return false;
    px[0] = (0.5f * view->fx * x / depth + 0.5f) * (float)view->width;
    px[1] = (0.5f * view->fy * y / depth + 0.5f) * (float)view->height;
    return isfinite(px[0]) && isfinite(px[1]);
}

/* The pixel rectangle (x, y, w, h) holding every floor point whose sun ray
 * (either way) meets the shadow's box: the box's corners moved along the sun
 * onto the floor, seen by the camera. Elsewhere the map's thickness is 0
 * and the sunlight the same as without a shadow. False when there is none to
 * find (a corner behind the camera, the sun at the horizon). */
static bool shadow_rect(const fc_view *view, const fc_environment *env, int rect[4])
{
    float sun_up = fc_dot3(env->sun, env->up);
    if (!(sun_up > 1e-3f))
        return false;
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int corner = 0; corner < 8; corner++) {
        float c[3], onto_floor[3], px[2];
        for (int i = 0; i < 3; i++)
            c[i] = (corner >> i) & 1 ? env->shadow_box_hi[i] : env->shadow_box_lo[i];
        float along = (fc_dot3(c, env->up) - env->floor_height) / sun_up;
        for (int i = 0; i < 3; i++)
            onto_floor[i] = c[i] - along * env->sun[i];
        if (!to_pixels(view, onto_floor, px))
            return false;
        for (int i = 0; i < 2; i++) {
            lo[i] = fminf(lo[i], px[i]);
            hi[i] = fmaxf(hi[i], px[i]);
        }
    }
    const float size[2] = {(float)view->width, (float)view->height};
    int bounds[4];
    for (int i = 0; i < 2; i++) {
        float a = fmaxf(floorf(lo[i]) - SHADOW_RECT_MARGIN_PX, 0.0f);
        float b = fminf(ceilf(hi[i]) + SHADOW_RECT_MARGIN_PX, size[i]);
        bounds[i] = (int)a;
        bounds[i + 2] = b > a ? (int)b : (int)a;
    }
    rect[0] = bounds[0];
    rect[1] = bounds[1];
    rect[2] = bounds[2] - bounds[0];
    rect[3] = bounds[3] - bounds[1];
    return true;
}

static int add_scissored(fc_background_draw *draws, int n, const fc_background_draw *like, unsigned features, int x,
                         int y, int w, int h)
{
    if (w <= 0 || h <= 0)
        return n;
    draws[n] = *like;
    draws[n].features = features;
    draws[n].scissored = true;
    draws[n].scissor[0] = x;
    draws[n].scissor[1] = y;
    draws[n].scissor[2] = w;
    draws[n].scissor[3] = h;
    return n + 1;
}

/* The floor below the line: with the shadow's lookup inside its rectangle,
 * without it in the four strips around (when the rectangle is known and no
 * mesh casts a shadow, which may fall anywhere). */
static int floor_draws(const fc_view *view, const fc_environment *env, unsigned features,
                       const fc_background_draw *floor, fc_background_draw *draws, int n)
{
    int r[4];
    if (!(features & FC_FEATURE_SHADOW) || (features & FC_FEATURE_MESH_SHADOW) || !shadow_rect(view, env, r)) {
        draws[n] = *floor;
        return n + 1;
    }
    unsigned lit = features & ~(unsigned)FC_FEATURE_SHADOW;
    int w = (int)view->width, h = (int)view->height;
    n = add_scissored(draws, n, floor, features, r[0], r[1], r[2], r[3]);
    n = add_scissored(draws, n, floor, lit, 0, 0, w, r[1]);
    n = add_scissored(draws, n, floor, lit, 0, r[1] + r[3], w, h - r[1] - r[3]);
    n = add_scissored(draws, n, floor, lit, 0, r[1], r[0], r[3]);
    n = add_scissored(draws, n, floor, lit, r[0] + r[2], r[1], w - r[0] - r[2], r[3]);
    return n;
}

int fc_background_regions(const fc_view *view, const fc_environment *env, unsigned features,
                          fc_background_draw draws[FC_BACKGROUND_DRAWS_MAX])
{
    float line[3], g;
    if (!(features & FC_FEATURE_FLOOR) || !horizon_line(view, env, line, &g)) {
        draws[0] = unclipped(features);
        return 1;
    }
    const unsigned floor_features = FC_FEATURE_FLOOR | FC_FEATURE_SHADOW | FC_FEATURE_MESH_SHADOW;
    int n = 0;
    /* The sky: a x + b y + c >= margin. */
    draws[n] = unclipped(features & ~floor_features);
    set_plane(draws[n++].clip_planes[0], line[0], line[1], line[2] - REGION_MARGIN_PX * g);
    /* The band: |a x + b y + c| <= half width, the general program. */
    draws[n] = unclipped(features);
    set_plane(draws[n].clip_planes[0], line[0], line[1], line[2] + BAND_HALF_WIDTH_PX * g);
    set_plane(draws[n++].clip_planes[1], -line[0], -line[1], BAND_HALF_WIDTH_PX * g - line[2]);
    /* The floor: a x + b y + c <= -margin. */
    fc_background_draw floor = unclipped(features | FC_FEATURE_FLOOR_ONLY);
    set_plane(floor.clip_planes[0], -line[0], -line[1], -line[2] - REGION_MARGIN_PX * g);
    return floor_draws(view, env, features | FC_FEATURE_FLOOR_ONLY, &floor, draws, n);
}
