/* test_shadow_sun_depth.c — the fluid's depth from the sun is splatted only
 * for meshes (shadow_pass.h): environment.frag.glsl reads it in
 * in_front_of_fluid, which only a mesh's surface reaches, so a shadowed
 * render without meshes splats the thickness alone (no depth, no pinhole
 * fill, no resolve). A ball of particles above the floor, shadow on, with the
 * shadow pass's splat forced to each method in turn:
 *  (a) without meshes the sun's depth target is never allocated (the
 *      pipeline's warm-up leaves the shadow pass trimmed), env has none, and
 *      the shadow map holds the ball's thickness;
 *  (b) with an opaque box hidden inside the ball (the scene's box, so the
 *      sun's camera, unchanged) the depth is splatted: fluid depth at the
 *      map's centre, 0 in its corner, and the shadow map is the same as
 *      without the box to a millionth: leaving the depth out changes no
 *      thickness (not bit for bit: the two runs' passes meet texel centres
 *      through texture coordinates that are not exact in binary, as no
 *      texture's extent is a power of two, gl_util.h's fc_gl_non_pot);
 *  (c) without the box again, after a run that splatted both, the shadow map
 *      is that of (a) to a millionth and the 8-bit image bit for bit (no
 *      state of the depth run leaks into the thickness-only one). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define WIDTH 96
#define HEIGHT 72
#define EYE 4.0
#define LATTICE 0.0625f
#define STEPS 6
#define RADIUS 0.05f
#define HIDDEN_HALF 0.1f   /* the box inside the ball: half its side */

/* A cube of half side `half` around the origin: 8 corners, 12 triangles. */
static fc_mesh_buffers *hidden_box(render_fixture *f, float half, float vertices[24], uint32_t indices[36])
{
    for (int c = 0; c < 8; c++)
        for (int a = 0; a < 3; a++)
            vertices[3 * c + a] = (c >> a) & 1 ? half : -half;
    static const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int q = 0; q < 6; q++) {
        const uint32_t *v = quads[q];
        uint32_t tri[6] = {v[0], v[1], v[2], v[0], v[2], v[3]};
        memcpy(indices + 6 * q, tri, sizeof tri);
    }
    fc_mesh mesh = {.vertex_count = 8, .triangle_count = 12, .vertices = vertices, .indices = indices,
                    .opacity = 1.0f};
    fc_mesh_buffers *buffers = NULL;
    fc_error err = {0};
    fc_code code = fc_mesh_buffers_create(f->pipeline, &mesh, &buffers, &err);
    CHECK_MSG(code == FC_OK, "mesh buffers: %s", err.message);
    return code == FC_OK ? buffers : NULL;
}

typedef struct shadow_render {
    fc_image color;       /* 8-bit */
    fc_image map;         /* the shadow map (R32F thickness) */
    fc_image sun_depth;   /* the fluid's depth from the sun, when the run splatted it */
} shadow_render;

static void free_render(shadow_render *r)
{
    fc_image_free(&r->color);
    fc_image_free(&r->map);
    fc_image_free(&r->sun_depth);
}

/* One 8-bit render with `meshes` and the shadow pass's images read back. */
static bool render(render_fixture *f, const fc_scene_mesh *meshes, uint32_t count, shadow_render *out)
{
    memset(out, 0, sizeof *out);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = RADIUS;
    settings.shadow = 1;
    fc_camera cam = axis_camera(EYE, WIDTH, HEIGHT);
    fc_render_scene scene = {.meshes = meshes, .mesh_count = count};
    fc_error err = {0};
    fc_code code = fc_pipeline_render_with(f->pipeline, &cam, &settings, &scene, FC_AOV_COLOR, 1, &out->color, NULL,
                                           &err);
    CHECK_MSG(code == FC_OK, "render: %s", err.message);
    const fc_shadow_pass *shadow = fc_pipeline_shadow_pass(f->pipeline);
    if (code == FC_OK)
        code = read_target(&shadow->box, 1, &out->map, &err);
    if (code == FC_OK && shadow->splat.target.bytes > 0)
        code = read_target(&shadow->splat.target, 1, &out->sun_depth, &err);
    CHECK_MSG(code == FC_OK, "reading the shadow pass back: %s", err.message);
    return code == FC_OK;
}

static bool same_image(const fc_image *a, const fc_image *b)
{
    return a->width == b->width && a->height == b->height && a->channels == b->channels && a->type == b->type &&
           a->pixels && b->pixels && memcmp(a->pixels, b->pixels, fc_image_size(a)) == 0;
}

/* Two one-channel float maps of one size whose texels agree to a millionth
 * of the largest (a texel of thickness left out or added is far more). */
static bool same_map(const fc_image *a, const fc_image *b)
{
    if (a->width != b->width || a->height != b->height || !a->pixels || !b->pixels)
        return false;
    float largest = 0.0f, worst = 0.0f;
    for (uint32_t y = 0; y < a->height; y++)
        for (uint32_t x = 0; x < a->width; x++) {
            float va = pixel_f32(a, x, y), vb = pixel_f32(b, x, y);
            largest = fabsf(va) > largest ? fabsf(va) : largest;
            worst = fabsf(va - vb) > worst ? fabsf(va - vb) : worst;
        }
    return worst <= 1e-6f * largest;
}

static void check_method(render_fixture *f, fc_splat_method method, const fc_scene_mesh *box)
{
    const char *name = method == FC_SPLAT_COMPUTE ? "compute" : "fragment";
    fc_shadow_pass *shadow = fc_pipeline_shadow_pass(f->pipeline);
    fc_shadow_pass_trim(shadow);   /* as the warm-up leaves it */
    shadow->splat.method = method;
    shadow_render alone, with_box, again;
    bool ok = render(f, NULL, 0, &alone);
    /* (a) */
    CHECK_MSG(shadow->splat.last_used == method, "%s: the shadow's splat was not the one forced", name);
    CHECK_MSG(shadow->splat.target.bytes == 0, "%s: a render without meshes allocated the sun's depth (%llu bytes)",
              name, (unsigned long long)shadow->splat.target.bytes);
    CHECK_MSG(ok && image_sum(&alone.map) > 0.0, "%s: the shadow map holds no thickness", name);
    /* (b) */
    ok = ok && render(f, box, 1, &with_box);
    CHECK_MSG(shadow->splat.last_used == method, "%s: the shadow's splat was not the one forced", name);
    CHECK_MSG(ok && with_box.sun_depth.pixels, "%s: a render with a mesh splatted no depth from the sun", name);
    if (ok && with_box.sun_depth.pixels) {
        const fc_image *d = &with_box.sun_depth;
        float centre = pixel_f32(d, d->width / 2, d->height / 2), corner = pixel_f32(d, 0, 0);
        CHECK_MSG(centre > 0.0f && corner == 0.0f, "%s: sun depth %g at the map's centre, %g in its corner", name,
                  (double)centre, (double)corner);
    }
    CHECK_MSG(ok && same_map(&alone.map, &with_box.map),
              "%s: the shadow map splatted without the depth differs from the one splatted with it", name);
    /* (c) */
    ok = ok && render(f, NULL, 0, &again);
    CHECK_MSG(ok && same_map(&alone.map, &again.map), "%s: the shadow map changed after a depth run", name);
    CHECK_MSG(ok && same_image(&alone.color, &again.color), "%s: the image changed after a depth run", name);
    free_render(&alone);
    free_render(&with_box);
    free_render(&again);
}

int main(void)
{
    render_fixture f;
    if (!fixture_open(&f))
        return 1;
    uint64_t count = 0;
    float *positions = lattice_ball(STEPS, LATTICE, 0.0f, &count);
    float vertices[24];
    uint32_t indices[36];
    fc_mesh_buffers *buffers = positions ? hidden_box(&f, HIDDEN_HALF, vertices, indices) : NULL;
    fc_frame frame = {.count = count, .positions = positions};
    fc_error err = {0};
    fc_code code = buffers ? fc_pipeline_upload(f.pipeline, &frame, NULL, &err) : FC_ERR_NOMEM;
    CHECK_MSG(code == FC_OK, "upload: %s", err.message);
    if (code == FC_OK) {
        fc_scene_mesh box = {.buffers = buffers, .color = {0.8f, 0.2f, 0.2f}, .opacity = 1.0f};
        box.transform[0] = box.transform[5] = box.transform[10] = 1.0f;   /* 3x4: identity */
        check_method(&f, FC_SPLAT_COMPUTE, &box);
        check_method(&f, FC_SPLAT_FRAGMENT, &box);
    }
    fc_mesh_buffers_destroy(buffers);
    free(positions);
    fixture_close(&f);
    return test_result();
}
