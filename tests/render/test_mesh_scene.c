/* test_mesh_scene.c — meshes in the picture (issue 14, PROTOCOL.md section
 * 12), through the real pipeline on llvmpipe. The camera looks down -z from
 * (0, 0, 4) at a ball of particles (centres within 0.5 of the origin,
 * radius 0.05), up +y, so the floor lies below the scene along -y.
 *  (a) An opaque box in front of the ball's left half (x < 0, z in [0.7,
 *      0.9]) hides the fluid there: the depth AOV is 0 behind the box and
 *      the analytic ball depth on the right half; the colour there is the
 *      box's (red box: red, green box: green) while fluid pixels away from
 *      the box do not depend on its colour.
 *  (b) The same box as glass (opacity 0.3) hides nothing (the depth AOV is
 *      the ball's) but tints: the colour moves from the box's absence
 *      (opacity 0: counted in the bounds, not drawn) towards the opaque box,
 *      by less than the opaque box moves it.
 *  (c) A particle inside an opaque box is not drawn in front of it: a
 *      sphere wholly inside leaves depth 0; one whose cap pokes out of the
 *      box's front face (z 0.5) shows only the cap, at the cap's depth.
 *  (d) A closed tank around the ball hides it (depth 0 at the centre), but
 *      not with hide_near: the near wall is culled and the fluid's depth is
 *      the ball's, while the far wall shows around the ball.
 *  (e) An opaque box above the floor casts a shadow on it (shadow on): floor
 *      pixels darken against the box being absent. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_frame.h"
#include "render_fixture.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 72
#define EYE 4.0
#define LATTICE 0.0625f
#define STEPS 8
#define RADIUS 0.05f
#define BALL_FRONT (EYE - STEPS * LATTICE - RADIUS)   /* 3.45 at the centre pixel */

/* A box [lo, hi] of 8 corners and 12 triangles wound counter-clockwise seen from outside. */
typedef struct box {
    float vertices[24];
    uint32_t indices[36];
    fc_mesh_buffers *buffers;
} box;

static bool box_make(render_fixture *f, box *b, const float lo[3], const float hi[3])
{
    for (int c = 0; c < 8; c++) {
        b->vertices[3 * c] = c & 1 ? hi[0] : lo[0];
        b->vertices[3 * c + 1] = c & 2 ? hi[1] : lo[1];
        b->vertices[3 * c + 2] = c & 4 ? hi[2] : lo[2];
    }
    /* Faces as corner quads (a b c d counter-clockwise from outside). */
    static const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int q = 0; q < 6; q++) {
        const uint32_t *v = quads[q];
        uint32_t tri[6] = {v[0], v[1], v[2], v[0], v[2], v[3]};
        memcpy(b->indices + 6 * q, tri, sizeof tri);
    }
    fc_mesh mesh = {.vertex_count = 8, .triangle_count = 12, .vertices = b->vertices, .indices = b->indices,
                    .opacity = 1.0f};
    fc_error err;
    fc_code code = fc_mesh_buffers_create(f->pipeline, &mesh, &b->buffers, &err);
    CHECK_MSG(code == FC_OK, "mesh buffers: %s", err.message);
    return code == FC_OK;
}

static fc_scene_mesh placed(const box *b, float r, float g, float bl, float opacity, bool hide_near)
{
    fc_scene_mesh m = {.buffers = b->buffers, .color = {r, g, bl}, .opacity = opacity, .hide_near = hide_near};
    m.transform[0] = m.transform[5] = m.transform[10] = 1.0f;
    return m;
}

typedef struct scene_render {
    fc_image image;
    fc_code code;
} scene_render;

/* Renders the uploaded frame with `meshes`. */
static void render(render_fixture *f, const fc_scene_mesh *meshes, uint32_t count, fc_aov aov, int want_u8,
                   const fc_settings *settings, scene_render *out)
{
    fc_camera cam = axis_camera(EYE, WIDTH, HEIGHT);
    fc_render_scene scene = {.meshes = meshes, .mesh_count = count};
    fc_error err;
    memset(&out->image, 0, sizeof out->image);
    out->code = fc_pipeline_render_with(f->pipeline, &cam, settings, &scene, aov, want_u8, &out->image, NULL, &err);
    CHECK_MSG(out->code == FC_OK, "render: %s", err.message);
}

/* FC_TEST_DUMP=DIR writes the colour images as PPM files there, to look at. */
static void dump(const fc_image *img, const char *name)
{
    const char *dir = getenv("FC_TEST_DUMP");
    if (!dir || img->type != FC_PIXEL_U8)
        return;
    char path[512];
    snprintf(path, sizeof path, "%s/%s.ppm", dir, name);
    FILE *out = fopen(path, "wb");
    if (!out)
        return;
    fprintf(out, "P6 %u %u 255\n", img->width, img->height);
    for (size_t i = 0; i < (size_t)img->width * img->height; i++)
        fwrite((const uint8_t *)img->pixels + 4 * i, 1, 3, out);
    fclose(out);
}

static const uint8_t *rgba(const fc_image *img, uint32_t x, uint32_t row)
{
    return (const uint8_t *)img->pixels + ((size_t)row * img->width + x) * 4;
}

/* Pixel column of world x at the depth of the ball's front, row of world y. */
static void project(double x, double y, double z, uint32_t *px, uint32_t *row)
{
    fc_camera cam = axis_camera(EYE, WIDTH, HEIGHT);
    double point[3] = {x, y, z}, fx, fr;
    analytic_project(&cam, point, &fx, &fr);
    *px = (uint32_t)fx;
    *row = (uint32_t)fr;
}

static void test_opaque_box(render_fixture *f, const fc_settings *s)
{
    box b;
    if (!box_make(f, &b, (float[3]){-1.5f, -1.5f, 0.7f}, (float[3]){0.0f, 1.5f, 0.9f}))
        return;
    fc_scene_mesh red = placed(&b, 1, 0, 0, 1, false), green = placed(&b, 0, 1, 0, 1, false);
    scene_render depth, with_red, with_green, none_depth;
    render(f, NULL, 0, FC_AOV_DEPTH, 0, s, &none_depth);
    render(f, &red, 1, FC_AOV_DEPTH, 0, s, &depth);
    render(f, &red, 1, FC_AOV_COLOR, 1, s, &with_red);
    render(f, &green, 1, FC_AOV_COLOR, 1, s, &with_green);
    dump(&with_red.image, "opaque_red");
    if (depth.code == FC_OK && with_red.code == FC_OK && with_green.code == FC_OK && none_depth.code == FC_OK) {
        /* Behind the box: the left half of the ball, inside its silhouette. */
        int hidden = 0, shown = 0, checked = 0;
        for (double x = -0.4; x <= -0.1; x += 0.1)
            for (double y = -0.3; y <= 0.3; y += 0.1) {
                uint32_t px, row;
                if (x * x + y * y > 0.4 * 0.4)
                    continue;   /* the ball's rim: its silhouette is a pixel either way */
                project(x, y, 0.5, &px, &row);
                checked++;
                hidden += pixel_f32(&none_depth.image, px, row) > 0.0f && pixel_f32(&depth.image, px, row) == 0.0f;
                const uint8_t *r = rgba(&with_red.image, px, row), *g = rgba(&with_green.image, px, row);
                CHECK_MSG(r[0] > 2 * r[1] + 10 && g[1] > 2 * g[0] + 10, "box colour at (%u, %u): red %u %u %u green %u %u %u",
                          px, row, r[0], r[1], r[2], g[0], g[1], g[2]);
            }
        CHECK_MSG(hidden == checked, "fluid hidden behind the box at %d of %d pixels", hidden, checked);
        /* The right half: the ball's depth as without the box, colours independent of the box's. */
        for (double x = 0.15; x <= 0.35; x += 0.1)
            for (double y = -0.2; y <= 0.2; y += 0.1) {
                uint32_t px, row;
                project(x, y, 0.5, &px, &row);
                float d = pixel_f32(&depth.image, px, row), d0 = pixel_f32(&none_depth.image, px, row);
                shown += d > 0.0f && fabsf(d - d0) < 1e-4f;
                const uint8_t *r = rgba(&with_red.image, px, row), *g = rgba(&with_green.image, px, row);
                CHECK_MSG(abs(r[0] - g[0]) <= 3 && abs(r[1] - g[1]) <= 3 && abs(r[2] - g[2]) <= 3,
                          "fluid at (%u, %u) depends on the box's colour", px, row);
            }
        CHECK_MSG(shown == 15, "fluid shown beside the box at %d of 15 pixels", shown);
        uint32_t px, row;
        project(0.0, 0.0, 0.5, &px, &row);
        printf("opaque box: %d/%d hidden, centre-right depth %.3f (analytic front %.3f)\n", hidden, checked,
               (double)pixel_f32(&depth.image, px + 2, row), BALL_FRONT);
    }
    fc_image_free(&depth.image);
    fc_image_free(&none_depth.image);
    fc_image_free(&with_red.image);
    fc_image_free(&with_green.image);

    /* (b) Glass: the same box at opacity 0.3 tints, hides nothing. */
    fc_scene_mesh glass = placed(&b, 0.1f, 0.3f, 1.0f, 0.3f, false), absent = placed(&b, 0.1f, 0.3f, 1.0f, 0, false),
                  solid = placed(&b, 0.1f, 0.3f, 1.0f, 1, false);
    scene_render g_depth, g_color, a_color, s_color;
    render(f, &glass, 1, FC_AOV_DEPTH, 0, s, &g_depth);
    render(f, &glass, 1, FC_AOV_COLOR, 1, s, &g_color);
    render(f, &absent, 1, FC_AOV_COLOR, 1, s, &a_color);
    render(f, &solid, 1, FC_AOV_COLOR, 1, s, &s_color);
    dump(&g_color.image, "glass");
    dump(&a_color.image, "glass_absent");
    if (g_depth.code == FC_OK && g_color.code == FC_OK && a_color.code == FC_OK && s_color.code == FC_OK) {
        int tinted = 0, visible = 0, n = 0;
        for (double x = -0.4; x <= -0.1; x += 0.1)
            for (double y = -0.3; y <= 0.3; y += 0.1) {
                uint32_t px, row;
                if (x * x + y * y > 0.4 * 0.4)
                    continue;
                project(x, y, 0.5, &px, &row);
                n++;
                visible += pixel_f32(&g_depth.image, px, row) > 0.0f;
                const uint8_t *gl = rgba(&g_color.image, px, row), *ab = rgba(&a_color.image, px, row),
                              *so = rgba(&s_color.image, px, row);
                int moved = 0, full = 0;
                for (int c = 0; c < 3; c++) {
                    moved += abs(gl[c] - ab[c]);
                    full += abs(so[c] - ab[c]);
                }
                tinted += moved >= 6 && moved < full && gl[2] >= ab[2];
            }
        CHECK_MSG(visible == n, "fluid behind glass visible at %d of %d pixels", visible, n);
        CHECK_MSG(tinted == n, "glass tints (less than opaque, towards blue) at %d of %d pixels", tinted, n);
        printf("glass: fluid visible at %d/%d, tinted at %d/%d\n", visible, n, tinted, n);
    }
    fc_image_free(&g_depth.image);
    fc_image_free(&g_color.image);
    fc_image_free(&a_color.image);
    fc_image_free(&s_color.image);
    fc_mesh_buffers_destroy(b.buffers);
}

/* (c) A particle inside a box; one whose cap pokes out of its front face. */
static void test_particle_inside(render_fixture *f)
{
    box b;
    if (!box_make(f, &b, (float[3]){-0.5f, -0.5f, -0.5f}, (float[3]){0.5f, 0.5f, 0.5f}))
        return;
    const float r = 0.1f;
    float positions[6] = {-0.25f, 0.0f, 0.0f, 0.25f, 0.0f, 0.45f};   /* inside; cap out to z 0.55 */
    fc_frame frame = {.count = 2, .positions = positions};
    fc_error err;
    CHECK_CODE(fc_pipeline_upload(f->pipeline, &frame, NULL, &err), FC_OK);
    fc_settings s = test_settings(r, FC_SMOOTHING_NONE, 0);
    fc_scene_mesh m = placed(&b, 0.5f, 0.5f, 0.5f, 1, false);
    scene_render with, without;
    render(f, NULL, 0, FC_AOV_DEPTH, 0, &s, &without);
    render(f, &m, 1, FC_AOV_DEPTH, 0, &s, &with);
    if (with.code == FC_OK && without.code == FC_OK) {
        uint32_t px, row;
        project(-0.25, 0.0, 0.1, &px, &row);
        CHECK_MSG(pixel_f32(&without.image, px, row) > 0.0f && pixel_f32(&with.image, px, row) == 0.0f,
                  "the particle inside the box is drawn: %g", (double)pixel_f32(&with.image, px, row));
        project(0.25, 0.0, 0.55, &px, &row);
        float cap = pixel_f32(&with.image, px, row);
        CHECK_MSG(fabsf(cap - (float)(EYE - 0.55)) < 0.01f, "the cap's depth %g, expected %g", (double)cap,
                  EYE - 0.55);
        /* Every pixel of the poking sphere, solved analytically: where its
         * front lies behind the box's face (depth 3.5) it is hidden, where in
         * front it keeps its depth. */
        fc_camera cam = axis_camera(EYE, WIDTH, HEIGHT);
        const double centre[3] = {0.25, 0.0, 0.45};
        int hidden = 0, behind = 0, kept = 0, in_front = 0;
        for (uint32_t y = 0; y < HEIGHT; y++)
            for (uint32_t x = 0; x < WIDTH; x++) {
                double edge, d = analytic_sphere_depth(&cam, centre, r, x, y, &edge);
                if (d <= 0.0 || edge < 0.05)
                    continue;
                float got = pixel_f32(&with.image, x, y);
                if (d > EYE - 0.5 + 0.01) {
                    behind++;
                    hidden += got == 0.0f;
                } else if (d < EYE - 0.5 - 0.01) {
                    in_front++;
                    kept += fabsf(got - (float)d) < 0.01f;
                }
            }
        CHECK_MSG(behind > 0 && hidden == behind, "sphere behind the face: %d of %d pixels hidden", hidden, behind);
        CHECK_MSG(in_front > 0 && kept == in_front, "cap in front of the face: %d of %d pixels kept", kept, in_front);
        int seen_without = in_front;
        printf("particle inside: cap depth %.3f (expected %.3f), rim hidden %d/%d\n", (double)cap, EYE - 0.55,
               hidden, seen_without);
    }
    fc_image_free(&with.image);
    fc_image_free(&without.image);
    fc_mesh_buffers_destroy(b.buffers);
}

/* (d) A closed tank around the ball, with and without hide_near. */
static void test_tank(render_fixture *f, const fc_settings *s)
{
    box b;
    if (!box_make(f, &b, (float[3]){-0.8f, -0.8f, -0.8f}, (float[3]){0.8f, 0.8f, 0.8f}))
        return;
    fc_scene_mesh closed = placed(&b, 0.9f, 0.6f, 0.2f, 1, false), open = placed(&b, 0.9f, 0.6f, 0.2f, 1, true);
    scene_render d_closed, d_open, d_none, c_open;
    render(f, NULL, 0, FC_AOV_DEPTH, 0, s, &d_none);
    render(f, &closed, 1, FC_AOV_DEPTH, 0, s, &d_closed);
    render(f, &open, 1, FC_AOV_DEPTH, 0, s, &d_open);
    render(f, &open, 1, FC_AOV_COLOR, 1, s, &c_open);
    dump(&c_open.image, "tank_hide_near");
    if (d_closed.code == FC_OK && d_open.code == FC_OK && d_none.code == FC_OK && c_open.code == FC_OK) {
        uint32_t px, row;
        project(0.0, 0.0, 0.5, &px, &row);
        CHECK_MSG(pixel_f32(&d_closed.image, px, row) == 0.0f, "the closed tank's near wall does not hide the fluid");
        float open_depth = pixel_f32(&d_open.image, px, row), none = pixel_f32(&d_none.image, px, row);
        CHECK_MSG(open_depth > 0.0f && fabsf(open_depth - none) < 1e-4f, "with hide_near the fluid's depth is %g, not %g",
                  (double)open_depth, (double)none);
        /* Inside the tank's outline, beside the ball: the far wall, orange. */
        project(0.7, 0.6, -0.8, &px, &row);
        const uint8_t *w = rgba(&c_open.image, px, row);
        CHECK_MSG(w[0] > w[2] + 40 && w[1] > w[2] + 10, "far wall at (%u, %u) is %u %u %u", px, row, w[0], w[1], w[2]);
        printf("tank: closed depth %.3f, hide_near depth %.3f (without %.3f), far wall %u %u %u\n",
               (double)pixel_f32(&d_closed.image, px, row), (double)open_depth, (double)none, w[0], w[1], w[2]);
    }
    fc_image_free(&d_closed.image);
    fc_image_free(&d_open.image);
    fc_image_free(&d_none.image);
    fc_image_free(&c_open.image);
    fc_mesh_buffers_destroy(b.buffers);
}

/* (e) A box floating above the floor beside the ball casts a shadow on the floor. */
static void test_shadow(render_fixture *f, fc_settings s)
{
    box b;
    if (!box_make(f, &b, (float[3]){0.7f, -0.3f, -0.3f}, (float[3]){1.0f, 0.0f, 0.0f}))
        return;
    /* A floor well below: one more particle low under the ball, out of view behind it. */
    s.shadow = 1;
    fc_scene_mesh cast = placed(&b, 0.8f, 0.8f, 0.8f, 1, false), absent = placed(&b, 0.8f, 0.8f, 0.8f, 0, false);
    scene_render with, without;
    render(f, &cast, 1, FC_AOV_COLOR, 0, &s, &with);
    render(f, &absent, 1, FC_AOV_COLOR, 0, &s, &without);
    if (with.code == FC_OK && without.code == FC_OK) {
        int darker = 0, brighter_far = 0;
        const float *a = with.image.pixels, *o = without.image.pixels;
        for (size_t i = 0; i < (size_t)WIDTH * HEIGHT; i++) {
            float la = a[4 * i] + a[4 * i + 1] + a[4 * i + 2], lo = o[4 * i] + o[4 * i + 1] + o[4 * i + 2];
            darker += la < 0.6f * lo;
            brighter_far += la > 1.5f * lo + 0.5f;
        }
        CHECK_MSG(darker >= 20, "the box's shadow darkens %d pixels", darker);
        printf("shadow: %d pixels darker by 40%%+ (%d much brighter: the box itself)\n", darker, brighter_far);
    }
    fc_image_free(&with.image);
    fc_image_free(&without.image);
    fc_mesh_buffers_destroy(b.buffers);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    uint64_t count;
    float *positions = lattice_ball(STEPS, LATTICE, 0.0f, &count);
    fc_frame frame = {.count = count, .positions = positions};
    fc_error err;
    CHECK_CODE(fc_pipeline_upload(f.pipeline, &frame, NULL, &err), FC_OK);
    fc_settings s = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    s.shadow = 0;
    test_opaque_box(&f, &s);
    test_tank(&f, &s);
    test_shadow(&f, s);
    test_particle_inside(&f);
    free(positions);
    fixture_close(&f);
    return test_result();
}
