/* test_shadow.c — the fluid's shadow on the built-in floor (issue 11): a ball
 * of particles floating above the floor, rendered in float colour with
 * settings.shadow on and off. Two particles lie on the floor out of view,
 * one on each side, so the floor (the lowest particle less the radius) is
 * well below the ball, and the particles' box is centred on the ball: the
 * shadow pass looks from a perspective sun camera 20 box radii away, whose
 * rays lean up to 3 degrees off the sun's direction at the box's edges (a
 * ball 2 units off the box's centre casts its shadow 0.06 x its cast length
 * further out). The shadow
 *  (a) changes nothing in the sky, and no fluid pixel except through the
 *      floor it shows: the floor behind it, the floor it refracts (within the
 *      composite's largest shift) or the floor it mirrors (its normal AOV
 *      reflects the view ray onto shadowed floor: the ball's rim towards its
 *      shadow does); the fluid itself is not shadowed;
 *  (b) only darkens;
 *  (c) lies where the ray from the floor point towards the sun meets the
 *      ball: more than 90% of the shadowed floor pixels see the sun past the
 *      ball within 1.5 of its radii, and every floor pixel whose sun ray goes
 *      through the ball's core (within half its radius) is in the umbra;
 *  (d) stands where the ball's centre projects along the sun onto the floor
 *      (the centroid of the floor area in shadow), so that raising the ball
 *      moves it away from the ball's foot along the sun's horizontal
 *      direction, by the rise over tan(elevation): a shadow that shows how
 *      high the fluid stands.
 * The sun's direction comes from environment.c (fc_environment_for_view),
 * checked here against its description: 35 degrees above the floor, behind
 * the camera on its right. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "environment.h"
#include "fc_frame.h"
#include "render_fixture.h"
#include "test_util.h"
#include "view.h"

#define WIDTH 240
#define HEIGHT 180
#define SPACING 0.04f
#define RADIUS 0.025f
#define BALL_CENTRES 0.25                   /* radius of the ball's particle centres */
#define BALL (BALL_CENTRES + RADIUS)        /* the ball's radius, its particles' surfaces included */
#define MAX_PARTICLES 2400
#define ANCHOR_OFFSET 4.0                   /* of the two particles on the floor, each side of the ball */
#define ANCHOR_SHADOW_REACH (8.0 * RADIUS)   /* a lone particle's shadow, blurred by the map */
#define SUN_ELEVATION_DEG 35.0
#define MAX_SHIFT_FRACTION 0.05             /* of the refraction's shift, composite.frag.glsl */
/* A pixel changed: a channel moved by more than this (relative above 1);
 * shadow off and on render the same pixels bit for bit where the map holds
 * no fluid. */
#define CHANGED 1e-6
/* A floor pixel is in shadow when it lost more than this share of its light. */
#define SHADOWED 0.02
/* Nearly all of the shadow lies where the sun ray passes within 1.5 ball
 * radii of the ball's centre; its faint tail (the map's blur, which grows
 * with the particles' box) within this many. */
#define SHADOW_REACH 2.0
/* The umbra: floor pixels behind the ball's core lose at least this share of
 * what the darkest floor pixel loses. */
#define UMBRA 0.8
/* Where the shadow stands: its centroid within this many ball radii of where
 * the centre casts it, and raising the ball moves it by the expected length
 * within this share. The checkers shift the edge of the soft shadow (the
 * fog's share of a pixel depends on its albedo): over camera and box
 * variations the centroid lay 0.001-0.028 from the cast centre (0-0.1 ball
 * radii) and the move within 7% of the expected one. */
#define CENTROID_TOLERANCE 0.15
#define MOVE_TOLERANCE 0.1

static const double UP[3] = {0.0, 1.0, 0.0};
static const double PI = 3.14159265358979323846;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Deterministic jitter in [-0.5, 0.5). */
static float jitter(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (float)(*state >> 8) / (float)(1u << 24) - 0.5f;
}

typedef struct scene {
    float positions[3 * MAX_PARTICLES];
    uint64_t count;
    double centre[3];        /* of the ball */
    double anchors[2][3];    /* the particles on the floor, out of view */
    double floor_height;     /* the lowest particle less the radius */
} scene;

/* A jittered ball of particles centred `height` above the floor at (x, z),
 * and a particle on the floor ANCHOR_OFFSET to each side of it. */
static void make_scene(scene *s, double x, double z, double height)
{
    uint32_t seed = 777u;
    s->count = 0;
    s->floor_height = -RADIUS;   /* the anchors' centres are at y = 0 */
    s->centre[0] = x, s->centre[1] = s->floor_height + height, s->centre[2] = z;
    int steps = (int)(BALL_CENTRES / SPACING);
    for (int i = -steps; i <= steps; i++)
        for (int j = -steps; j <= steps; j++)
            for (int k = -steps; k <= steps; k++) {
                double dx = i * (double)SPACING, dy = j * (double)SPACING, dz = k * (double)SPACING;
                if (dx * dx + dy * dy + dz * dz > BALL_CENTRES * BALL_CENTRES || s->count + 2 >= MAX_PARTICLES)
                    continue;
                float *p = s->positions + 3 * s->count++;
                p[0] = (float)(s->centre[0] + dx) + 0.15f * SPACING * jitter(&seed);
                p[1] = (float)(s->centre[1] + dy) + 0.15f * SPACING * jitter(&seed);
                p[2] = (float)(s->centre[2] + dz) + 0.15f * SPACING * jitter(&seed);
            }
    for (int a = 0; a < 2; a++) {
        s->anchors[a][0] = x + (a ? ANCHOR_OFFSET : -ANCHOR_OFFSET), s->anchors[a][1] = 0.0, s->anchors[a][2] = z;
        float *p = s->positions + 3 * s->count++;
        for (int i = 0; i < 3; i++)
            p[i] = (float)s->anchors[a][i];
    }
}

/* Looking down on the floor at 16 degrees: sky over the top sixth. */
static fc_camera scene_camera(void)
{
    return (fc_camera){.eye = {0.35f, 1.3f, 3.2f}, .target = {-0.45f, 0.35f, 0.0f}, .up = {0.0f, 1.0f, 0.0f},
                       .fov_y_deg = 40.0f, .width = WIDTH, .height = HEIGHT};
}

/* The view-space direction through the centre of pixel (x, row), at z = -1. */
static void pixel_direction(const fc_view *v, uint32_t x, uint32_t row, double d[3])
{
    d[0] = ((x + 0.5) / v->width * 2.0 - 1.0) / v->fx;
    d[1] = (1.0 - (row + 0.5) / v->height * 2.0) / v->fy;
    d[2] = -1.0;
}

static void to_world_direction(const fc_view *v, const double d[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = v->view_to_world[0 * 3 + r] * d[0] + v->view_to_world[1 * 3 + r] * d[1] +
                 v->view_to_world[2 * 3 + r] * d[2];
}

/* Where the ray from `origin` along `dir` meets the floor; false when it does not. */
static bool floor_hit(const double origin[3], const double dir[3], double floor_height, double hit[3],
                      double *distance)
{
    double height = dot3(origin, UP) - floor_height, descent = -dot3(dir, UP) / sqrt(dot3(dir, dir));
    if (!(height > 0.0 && descent > 0.0))
        return false;
    *distance = height / descent;
    double length = sqrt(dot3(dir, dir));
    for (int i = 0; i < 3; i++)
        hit[i] = origin[i] + *distance * dir[i] / length;
    return true;
}

/* Pixels right of the image's right edge where p projects (negative: left of it). */
static double pixels_beside(const fc_view *v, const double p[3])
{
    double q[3];
    for (int r = 0; r < 3; r++)
        q[r] = v->view[0 * 4 + r] * p[0] + v->view[1 * 4 + r] * p[1] + v->view[2 * 4 + r] * p[2] + v->view[12 + r];
    return (v->fx * q[0] / -q[2] + 1.0) * 0.5 * v->width - v->width;
}

/* Distance from `centre` to the ray from `p` towards the sun. */
static double sun_ray_miss(const double p[3], const double sun[3], const double centre[3])
{
    double to_centre[3] = {centre[0] - p[0], centre[1] - p[1], centre[2] - p[2]};
    double t = fmax(dot3(to_centre, sun), 0.0);
    double miss[3];
    for (int i = 0; i < 3; i++)
        miss[i] = p[i] + t * sun[i] - centre[i];
    return sqrt(dot3(miss, miss));
}

/* Whether the sun ray from floor point p passes the fluid: within
 * SHADOW_REACH radii of the ball, or close by a particle on the floor (their
 * shadows, out of view, show in the ball's reflections). */
static bool sun_ray_blocked(const scene *s, const double p[3], const double sun[3])
{
    bool blocked = sun_ray_miss(p, sun, s->centre) < SHADOW_REACH * BALL;
    for (int a = 0; a < 2; a++)
        blocked |= sun_ray_miss(p, sun, s->anchors[a]) < ANCHOR_SHADOW_REACH;
    return blocked;
}

typedef struct images {
    fc_image on, off, depth, smoothed, normal;
} images;

static void render_images(render_fixture *f, const scene *s, const fc_camera *cam, images *im)
{
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = RADIUS;
    settings.shadow = 1;
    CHECK_CODE(render_positions(f, s->positions, s->count, cam, &settings, FC_AOV_COLOR, 0, &im->on), FC_OK);
    CHECK_CODE(render_positions(f, s->positions, s->count, cam, &settings, FC_AOV_DEPTH, 0, &im->depth), FC_OK);
    CHECK_CODE(render_positions(f, s->positions, s->count, cam, &settings, FC_AOV_SMOOTHED_DEPTH, 0, &im->smoothed),
               FC_OK);
    CHECK_CODE(render_positions(f, s->positions, s->count, cam, &settings, FC_AOV_NORMAL, 0, &im->normal), FC_OK);
    settings.shadow = 0;
    CHECK_CODE(render_positions(f, s->positions, s->count, cam, &settings, FC_AOV_COLOR, 0, &im->off), FC_OK);
}

static void free_images(images *im)
{
    fc_image_free(&im->on);
    fc_image_free(&im->off);
    fc_image_free(&im->depth);
    fc_image_free(&im->smoothed);
    fc_image_free(&im->normal);
}

static float channel(const fc_image *img, uint32_t x, uint32_t row, uint32_t c)
{
    return ((const float *)img->pixels)[((size_t)row * img->width + x) * img->channels + c];
}

typedef struct shadow_report {
    int sky, changed, changed_sky, brightened;
    int changed_fluid, fluid_behind, fluid_refracted, fluid_reflected, fluid_unexplained;
    int shadowed, shadowed_near_ball;   /* near: the sun ray passes within 1.5 ball radii */
    double farthest_miss;               /* of the shadowed pixels' sun rays, in ball radii */
    double farthest_change;             /* of the changed floor pixels' sun rays, in ball radii */
    int core;                           /* floor pixels whose sun ray passes within half a ball radius */
    double weakest_core, deepest;       /* the least darkening among them, the most over the floor */
    double centroid[3];                 /* of the floor area in shadow (darker by SHADOWED) */
} shadow_report;

/* Per pixel: what it shows and how the shadow changed it. */
typedef struct pixel_info {
    bool sky, fluid, changed;
    double darkening;   /* 1 - lit on / lit off */
} pixel_info;

/* Whether the fluid pixel (x, row) mirrors shadowed floor: the view ray
 * reflected at its smoothed surface (depth and normal AOVs) meets the floor
 * where the fluid blocks the sun. */
static bool reflects_shadow(const images *im, const fc_view *v, const scene *s, const double sun[3], uint32_t x,
                            uint32_t row)
{
    double z = channel(&im->smoothed, x, row, 0), d[3], n[3], point[3], origin[3], reflected[3], world[3];
    pixel_direction(v, x, row, d);
    for (int i = 0; i < 3; i++) {
        point[i] = d[i] * z;
        n[i] = channel(&im->normal, x, row, (uint32_t)i);
    }
    double length = sqrt(dot3(d, d)), dn = dot3(d, n) / length;
    for (int i = 0; i < 3; i++)
        reflected[i] = d[i] / length - 2.0 * dn * n[i];
    to_world_direction(v, point, origin);
    for (int i = 0; i < 3; i++)
        origin[i] += v->eye[i];
    to_world_direction(v, reflected, world);
    double hit[3], distance;
    return floor_hit(origin, world, s->floor_height, hit, &distance) && sun_ray_blocked(s, hit, sun);
}

/* Whether a changed floor pixel lies within the refraction's largest shift of (x, row). */
static bool refracts_shadow(const pixel_info *info, uint32_t x, uint32_t row)
{
    int reach_x = (int)ceil(MAX_SHIFT_FRACTION * WIDTH), reach_y = (int)ceil(MAX_SHIFT_FRACTION * HEIGHT);
    for (int dy = -reach_y; dy <= reach_y; dy++)
        for (int dx = -reach_x; dx <= reach_x; dx++) {
            int px = (int)x + dx, py = (int)row + dy;
            if (px < 0 || py < 0 || px >= WIDTH || py >= HEIGHT)
                continue;
            const pixel_info *q = &info[py * WIDTH + px];
            if (q->changed && !q->fluid)
                return true;
        }
    return false;
}

/* Shadow on and off compared pixel by pixel (a)-(c), and the centroid of
 * the shadow on the floor for (d). */
static shadow_report measure(render_fixture *f, const scene *s, const fc_camera *cam, const fc_view *v,
                             const double sun[3])
{
    static pixel_info info[WIDTH * HEIGHT];
    shadow_report r = {.weakest_core = 1.0};
    images im = {0};
    render_images(f, s, cam, &im);
    if (!im.on.pixels || !im.off.pixels || !im.depth.pixels || !im.smoothed.pixels || !im.normal.pixels) {
        CHECK_MSG(0, "no images");
        free_images(&im);
        return r;
    }
    double weight = 0.0;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++) {
            pixel_info *p = &info[row * WIDTH + x];
            double d[3], dir[3], hit[3], distance;
            pixel_direction(v, x, row, d);
            to_world_direction(v, d, dir);
            const double eye[3] = {v->eye[0], v->eye[1], v->eye[2]};
            p->sky = !floor_hit(eye, dir, s->floor_height, hit, &distance);
            p->fluid = channel(&im.depth, x, row, 0) > 0.0f || channel(&im.smoothed, x, row, 0) > 0.0f;
            double lit_on = 0.0, lit_off = 0.0;
            bool brighter = false;
            p->changed = false;
            for (uint32_t c = 0; c < 3; c++) {
                double a = channel(&im.on, x, row, c), b = channel(&im.off, x, row, c);
                p->changed |= fabs(a - b) > CHANGED * fmax(1.0, b);
                brighter |= a > b + CHANGED * fmax(1.0, b);
                lit_on += a;
                lit_off += b;
            }
            p->darkening = 1.0 - lit_on / lit_off;
            r.changed += p->changed;
            r.sky += p->sky;
            r.changed_sky += p->changed && p->sky;
            r.brightened += brighter;
            if (p->sky || p->fluid)
                continue;
            double miss = sun_ray_miss(hit, sun, s->centre);
            r.deepest = fmax(r.deepest, p->darkening);
            if (p->changed)
                r.farthest_change = fmax(r.farthest_change, miss / BALL);
            if (p->darkening > SHADOWED) {
                r.shadowed++;
                r.shadowed_near_ball += miss < 1.5 * BALL;
                r.farthest_miss = fmax(r.farthest_miss, miss / BALL);
            }
            if (miss < 0.5 * BALL) {
                r.core++;
                r.weakest_core = fmin(r.weakest_core, p->darkening);
            }
            /* The floor area the pixel covers: its solid angle (1/|d|^3 of the
             * central pixel's) x distance^2 / cos(incidence). Not weighted by
             * the darkening, which the checkers' albedo modulates through the
             * fog (a bias of a few percent). */
            double cos_incidence = -dot3(dir, UP) / sqrt(dot3(dir, dir)), length = sqrt(dot3(d, d));
            double w = (p->darkening > SHADOWED) * distance * distance / (cos_incidence * length * length * length);
            for (int i = 0; i < 3; i++)
                r.centroid[i] += w * hit[i];
            weight += w;
        }
    for (int i = 0; i < 3; i++)
        r.centroid[i] /= weight > 0.0 ? weight : 1.0;

    /* Changed fluid pixels, and the floor they show that explains it. */
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t x = 0; x < WIDTH; x++) {
            const pixel_info *p = &info[row * WIDTH + x];
            if (!p->changed || !p->fluid)
                continue;
            r.changed_fluid++;
            double d[3], dir[3], hit[3], distance;
            pixel_direction(v, x, row, d);
            to_world_direction(v, d, dir);
            const double eye[3] = {v->eye[0], v->eye[1], v->eye[2]};
            if (floor_hit(eye, dir, s->floor_height, hit, &distance) && sun_ray_blocked(s, hit, sun))
                r.fluid_behind++;
            else if (refracts_shadow(info, x, row))
                r.fluid_refracted++;
            else if (reflects_shadow(&im, v, s, sun, x, row))
                r.fluid_reflected++;
            else
                r.fluid_unexplained++;
        }
    free_images(&im);
    return r;
}

/* Where the ball's centre casts its shadow: along the sun onto the floor. */
static void expected_shadow_centre(const scene *s, const double sun[3], double out[3])
{
    double t = (dot3(s->centre, UP) - s->floor_height) / dot3(sun, UP);
    for (int i = 0; i < 3; i++)
        out[i] = s->centre[i] - t * sun[i];
}

static void check_shadow(const shadow_report *r, const scene *s, const double sun[3], const char *what)
{
    double near_share = r->shadowed ? (double)r->shadowed_near_ball / r->shadowed : 0.0;
    printf("%s: %d pixels changed, %d in the sky (of %d), %d brighter; %d fluid pixels changed: %d show shadowed floor "
           "behind them, %d refract it, %d reflect it, %d otherwise\n",
           what, r->changed, r->changed_sky, r->sky, r->brightened, r->changed_fluid, r->fluid_behind,
           r->fluid_refracted, r->fluid_reflected, r->fluid_unexplained);
    printf("%s: %d floor pixels shadowed, %.1f%% with the sun ray within 1.5 ball radii (farthest %.2f radii, of "
           "any change %.2f); %d behind the core, darkened %.3f at least, the darkest floor %.3f\n",
           what, r->shadowed, 100.0 * near_share, r->farthest_miss, r->farthest_change, r->core, r->weakest_core,
           r->deepest);
    /* (a) and (b) */
    CHECK_MSG(r->changed > 300, "%s: the shadow changed only %d pixels", what, r->changed);
    CHECK_MSG(r->sky > WIDTH * HEIGHT / 20, "%s: only %d sky pixels", what, r->sky);
    CHECK_MSG(r->changed_sky == 0, "%s: %d sky pixels changed", what, r->changed_sky);
    CHECK_MSG(r->fluid_unexplained == 0, "%s: %d fluid pixels changed without showing shadowed floor", what,
              r->fluid_unexplained);
    CHECK_MSG(r->changed_fluid < r->changed / 10, "%s: %d of the %d changed pixels are fluid", what, r->changed_fluid,
              r->changed);
    CHECK_MSG(r->brightened == 0, "%s: %d pixels brighter with the shadow", what, r->brightened);
    /* (c) */
    CHECK_MSG(near_share > 0.9, "%s: %.1f%% of the shadow where the sun ray passes the ball within 1.5 radii", what,
              100.0 * near_share);
    CHECK_MSG(r->farthest_change < SHADOW_REACH, "%s: a floor pixel changed where the sun ray passes %.2f ball radii "
              "from the ball", what, r->farthest_change);
    CHECK_MSG(r->core > 100, "%s: only %d floor pixels behind the ball's core in view", what, r->core);
    CHECK_MSG(r->deepest > 0.3, "%s: the darkest shadow takes %.3f of the light", what, r->deepest);
    CHECK_MSG(r->weakest_core > UMBRA * r->deepest, "%s: a floor pixel behind the ball's core darkened only %.3f", what,
              r->weakest_core);
    /* (d) where the centre casts its shadow */
    double expected[3];
    expected_shadow_centre(s, sun, expected);
    double off[3] = {r->centroid[0] - expected[0], r->centroid[1] - expected[1], r->centroid[2] - expected[2]};
    printf("%s: shadow centroid (%.3f, %.3f, %.3f), the centre cast along the sun (%.3f, %.3f, %.3f): %.3f apart "
           "(ball radius %.3f)\n",
           what, r->centroid[0], r->centroid[1], r->centroid[2], expected[0], expected[1], expected[2],
           sqrt(dot3(off, off)), BALL);
    CHECK_MSG(sqrt(dot3(off, off)) < CENTROID_TOLERANCE * BALL, "%s: shadow centroid %.3f from where the centre "
              "casts it", what, sqrt(dot3(off, off)));
}

/* The sun environment.c places for this camera, checked against its description. */
static void sun_direction(const fc_camera *cam, const fc_view *view, double sun[3])
{
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = RADIUS;
    const float lo[3] = {-1.0f, -1.0f, -1.0f}, hi[3] = {1.0f, 1.0f, 1.0f};   /* the sun does not depend on them */
    fc_environment env;
    fc_environment_for_view(view, cam, lo, hi, &settings, true, false, &env);
    for (int i = 0; i < 3; i++)
        sun[i] = env.sun[i];
    double back[3] = {cam->eye[0] - cam->target[0], cam->eye[1] - cam->target[1], cam->eye[2] - cam->target[2]};
    double along = dot3(back, UP);
    for (int i = 0; i < 3; i++)
        back[i] -= along * UP[i];
    double right[3] = {UP[1] * back[2] - UP[2] * back[1], UP[2] * back[0] - UP[0] * back[2],
                       UP[0] * back[1] - UP[1] * back[0]};   /* up x backward */
    double elevation = asin(dot3(sun, UP)) * 180.0 / PI;
    double behind = dot3(sun, back) / sqrt(dot3(back, back)), rightwards = dot3(sun, right) / sqrt(dot3(right, right));
    printf("sun (%.3f, %.3f, %.3f): %.2f degrees high, %.3f behind the camera, %.3f to its right\n", sun[0], sun[1],
           sun[2], elevation, behind, rightwards);
    CHECK_NEAR(elevation, SUN_ELEVATION_DEG, 0.01);
    CHECK(behind > 0.0);
    CHECK(rightwards > 0.0);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    static scene low, high;
    const double ball_x = 0.1, ball_z = 0.0, low_height = 0.55, rise = 0.35;
    make_scene(&low, ball_x, ball_z, low_height);
    make_scene(&high, ball_x, ball_z, low_height + rise);
    fc_camera cam = scene_camera();
    fc_view view;
    const float lo[3] = {-1.0f, -1.0f, -1.0f}, hi[3] = {1.0f, 1.0f, 1.0f};   /* the depth planes do not matter */
    fc_view_from_camera(&cam, lo, hi, RADIUS, &view);
    double sun[3];
    sun_direction(&cam, &view, sun);

    /* The particles on the floor lie out of view, with their own shadows (a
     * few radii long). */
    double left = pixels_beside(&view, low.anchors[0]) + WIDTH, right = pixels_beside(&view, low.anchors[1]);
    printf("the particles on the floor project %.0f pixels left and %.0f right of the image\n", -left, right);
    CHECK(left < -0.1 * WIDTH);
    CHECK(right > 0.1 * WIDTH);

    shadow_report r_low = measure(&f, &low, &cam, &view, sun);
    check_shadow(&r_low, &low, sun, "ball low");
    shadow_report r_high = measure(&f, &high, &cam, &view, sun);
    check_shadow(&r_high, &high, sun, "ball high");

    /* (d) Raised by `rise`, the shadow moves that over tan(elevation) along
     * the sun's horizontal direction, away from the ball's foot. */
    double away[3], moved[3], sun_up = dot3(sun, UP);
    for (int i = 0; i < 3; i++) {
        away[i] = -(sun[i] - sun_up * UP[i]);
        moved[i] = r_high.centroid[i] - r_low.centroid[i];
    }
    double away_length = sqrt(dot3(away, away));
    for (int i = 0; i < 3; i++)
        away[i] /= away_length;
    double expected = rise / tan(SUN_ELEVATION_DEG * PI / 180.0);
    double along = dot3(moved, away), across = sqrt(fmax(dot3(moved, moved) - along * along, 0.0));
    printf("raised by %.2f: the shadow moved %.3f away from the foot along the sun (expected %.3f), %.3f across\n",
           rise, along, expected, across);
    CHECK_NEAR(along, expected, MOVE_TOLERANCE * expected);
    CHECK_MSG(across < MOVE_TOLERANCE * expected, "the shadow moved %.3f across the sun's direction", across);
    fixture_close(&f);
    return test_result();
}
