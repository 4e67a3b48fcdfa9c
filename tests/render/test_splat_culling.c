/* test_splat_culling.c — the compute splat's culling of hidden particles
 * (surface_splat.comp.glsl, FC_DEPTH_ONLY: the camera's depth where the
 * thickness is splatted apart). The culling may only change the work, never
 * the depth: with and without it the depth is the same bit for bit, on scenes
 * where most particles are hidden (a pool of particle layers seen at a slant,
 * as the benchmark's, with spheres about 4 and about 9 pixels across, and as
 * ellipsoids) and on a dense random cloud. And the tiles it culls against
 * hold what it relies on: the pool's front covers the tiles over the pool, in
 * front of the layers below, so that most of those are skipped. The
 * thickness at the default half resolution splatted in the same walk of the
 * particles as the culled depth (fc_compute_splat_run_fused), and with it the
 * shadow map's thickness where the sun sees spheres of at most 2x2 texels,
 * leaves the image the same bit for bit as splatted apart. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"
#include "view.h"

/* A pool of particle layers on a lattice, as bench/scene.c's. */
#define POOL_SIDE 80
#define POOL_LAYERS 6
#define SPACING 0.025f
#define POOL_PARTICLES (POOL_SIDE * POOL_SIDE * POOL_LAYERS)
#define RADIUS (0.9f * SPACING)
#define CLOUD_PARTICLES 30000
/* The culling's tiles (CULL_TILE_PX in compute_splat.c). */
#define TILE_PX 4

static float *pool_positions(void)
{
    float *x = malloc(3 * POOL_PARTICLES * sizeof *x);
    int n = 0;
    for (int k = 0; k < POOL_LAYERS; k++)
        for (int j = 0; j < POOL_SIDE; j++)
            for (int i = 0; i < POOL_SIDE; i++) {
                x[3 * n + 0] = ((float)i + 0.5f) * SPACING - 1.0f;
                x[3 * n + 1] = ((float)j + 0.5f) * SPACING - 1.0f;
                x[3 * n + 2] = ((float)k + 0.5f) * SPACING;
                n++;
            }
    return x;
}

/* A deterministic cloud in the unit cube (a 32-bit LCG). */
static float *cloud_positions(void)
{
    float *x = malloc(3 * CLOUD_PARTICLES * sizeof *x);
    uint32_t state = 2024u;
    for (int i = 0; i < 3 * CLOUD_PARTICLES; i++) {
        state = state * 1664525u + 1013904223u;
        x[i] = (float)(state >> 8) / 16777216.0f - 0.5f;
    }
    return x;
}

/* The benchmark's view of its pool: from above at a slant. */
static fc_camera slant_camera(uint32_t width, uint32_t height)
{
    fc_camera cam = {.eye = {2.0f, -2.9f, 1.9f}, .target = {0.0f, 0.0f, 0.05f}, .up = {0.0f, 0.0f, 1.0f},
                     .fov_y_deg = 40.0f, .width = width, .height = height};
    return cam;
}

/* The depth AOV with the culling on and off: the same bits, over at least min_covered pixels. */
static void check_same_depth(render_fixture *f, const char *name, const float *x, uint64_t count,
                             const fc_camera *cam, const fc_settings *settings, int min_covered)
{
    fc_compute_splat *splat = fc_pipeline_compute_splat(f->pipeline);
    fc_image culled = {0}, whole = {0};
    splat->cull = true;
    CHECK_CODE(render_positions(f, x, count, cam, settings, FC_AOV_DEPTH, 0, &culled), FC_OK);
    CHECK_MSG(fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_COMPUTE, "%s: not the compute splat", name);
    splat->cull = false;
    CHECK_CODE(render_positions(f, x, count, cam, settings, FC_AOV_DEPTH, 0, &whole), FC_OK);
    splat->cull = true;
    int covered = 0, differ = 0;
    for (uint32_t row = 0; row < cam->height; row++)
        for (uint32_t px = 0; px < cam->width; px++) {
            float a = pixel_f32(&culled, px, row), b = pixel_f32(&whole, px, row);
            covered += b > 0.0f;
            differ += a != b;
        }
    CHECK_MSG(covered >= min_covered, "%s: only %d pixels covered", name, covered);
    CHECK_MSG(differ == 0, "%s: %d of %d pixels differ with the culling", name, differ, covered);
    printf("%s: %d covered pixels, the same depth with and without the culling\n", name, covered);
    fc_image_free(&culled);
    fc_image_free(&whole);
}

/* The colour image (floats) with the thickness at half resolution splatted
 * with the depth and apart: the same bits. */
/* Returns whether the shadow map's thickness was splatted in the same walk too. */
static bool check_same_fused(render_fixture *f, const char *name, const float *x, uint64_t count,
                             const fc_camera *cam, float radius)
{
    fc_compute_splat *splat = fc_pipeline_compute_splat(f->pipeline);
    fc_settings settings = test_settings(radius, FC_SMOOTHING_NONE, 0);
    settings.thickness_scale = 0.5f;
    settings.shadow = 1;   /* the floor's shadow: its map's thickness may ride along */
    fc_image fused = {0}, apart = {0};
    CHECK_CODE(render_positions(f, x, count, cam, &settings, FC_AOV_COLOR, 0, &fused), FC_OK);
    CHECK_MSG(splat->last_fused, "%s: the thickness was not splatted with the depth", name);
    bool sun = splat->last_fused_sun;
    splat->fuse = false;
    CHECK_CODE(render_positions(f, x, count, cam, &settings, FC_AOV_COLOR, 0, &apart), FC_OK);
    CHECK_MSG(!splat->last_fused && !splat->last_fused_sun, "%s: the thickness was splatted with the depth", name);
    splat->fuse = true;
    CHECK(fused.channels == apart.channels && fused.type == FC_PIXEL_F32);
    size_t values = (size_t)cam->width * cam->height * fused.channels;
    int differ = 0;
    for (size_t i = 0; i < values; i++)
        differ += ((const float *)fused.pixels)[i] != ((const float *)apart.pixels)[i];
    CHECK_MSG(differ == 0, "%s: %d values differ with the thickness splatted with the depth", name, differ);
    printf("%s: the same colour image with the thickness%s splatted with the depth and apart\n", name,
           sun ? " and the shadow map's" : "");
    fc_image_free(&fused);
    fc_image_free(&apart);
    return sun;
}

/* The far tiles of the last culled run (rows bottom-up, as GL stores them). */
static uint32_t *read_far_tiles(render_fixture *f, uint32_t tiles_x, uint32_t tiles_y)
{
    fc_compute_splat *splat = fc_pipeline_compute_splat(f->pipeline);
    uint32_t *tiles = malloc((size_t)tiles_x * tiles_y * sizeof *tiles);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureSubImage(splat->far_tiles, 0, 0, 0, 0, (GLsizei)tiles_x, (GLsizei)tiles_y, 1, GL_RED_INTEGER,
                         GL_UNSIGNED_INT, (GLsizei)((size_t)tiles_x * tiles_y * sizeof *tiles), tiles);
    CHECK(glGetError() == GL_NO_ERROR);
    return tiles;
}

static float as_float(uint32_t bits)
{
    union { uint32_t u; float f; } v = {.u = bits};
    return v.f;
}

/* The pool's lower layers lie behind its front: at the tile of a lower
 * particle's centre, every pixel holds a splatted depth nearer than that
 * particle can reach, for most of them (those near the pool's edges may
 * show). The depth and projection are computed here from the view. */
static void check_tiles_hide_lower_layers(render_fixture *f, const float *x, const fc_camera *cam)
{
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    fc_image depth = {0};
    CHECK_CODE(render_positions(f, x, POOL_PARTICLES, cam, &settings, FC_AOV_DEPTH, 0, &depth), FC_OK);
    fc_image_free(&depth);
    uint32_t tiles_x = (cam->width + TILE_PX - 1) / TILE_PX, tiles_y = (cam->height + TILE_PX - 1) / TILE_PX;
    uint32_t *tiles = read_far_tiles(f, tiles_x, tiles_y);
    float lo[3] = {-1.0f, -1.0f, 0.0f}, hi[3] = {1.0f, 1.0f, POOL_LAYERS * SPACING};
    fc_view view;
    fc_view_from_camera(cam, lo, hi, RADIUS, &view);
    const float *m = view.view;
    int lower = 0, hidden = 0;
    for (int n = 2 * POOL_SIDE * POOL_SIDE; n < POOL_PARTICLES - 2 * POOL_SIDE * POOL_SIDE; n++) {
        const float *p = &x[3 * n];   /* the middle layers: two above, two below */
        float v[3];
        for (int r = 0; r < 3; r++)
            v[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
        float d = -v[2];
        float sx = (view.fx * v[0] / d + 1.0f) * 0.5f * (float)cam->width;
        float sy = (view.fy * v[1] / d + 1.0f) * 0.5f * (float)cam->height;
        if (sx < 0.0f || sy < 0.0f || sx >= (float)cam->width || sy >= (float)cam->height)
            continue;
        lower++;
        float farthest = as_float(tiles[(uint32_t)sy / TILE_PX * tiles_x + (uint32_t)sx / TILE_PX]);
        hidden += farthest < d - RADIUS;
    }
    CHECK_MSG(lower > 12000, "only %d particles of the middle layers in view", lower);
    CHECK_MSG(hidden > lower * 8 / 10, "%d of %d particles of the middle layers lie behind their tile's front",
              hidden, lower);
    printf("tiles: %d of %d particles of the middle layers behind their tile's front\n", hidden, lower);
    free(tiles);
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    fc_pipeline_force_splat(f.pipeline, FC_SPLAT_COMPUTE);
    float *pool = pool_positions(), *cloud = cloud_positions();
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    fc_camera small = slant_camera(320, 240), large = slant_camera(720, 540);
    check_same_depth(&f, "pool, spheres about 4 px", pool, POOL_PARTICLES, &small, &settings, 15000);
    check_same_depth(&f, "pool, spheres about 9 px", pool, POOL_PARTICLES, &large, &settings, 80000);
    fc_settings shaped = settings;
    shaped.kernel = FC_KERNEL_ANISOTROPIC;
    check_same_depth(&f, "pool, ellipsoids", pool, POOL_PARTICLES, &small, &shaped, 15000);
    fc_camera axis = axis_camera(2.5, 400, 240);
    fc_settings cloud_settings = test_settings(0.01f, FC_SMOOTHING_NONE, 0);
    check_same_depth(&f, "cloud", cloud, CLOUD_PARTICLES, &axis, &cloud_settings, 20000);
    check_tiles_hide_lower_layers(&f, pool, &large);
    check_same_fused(&f, "pool, spheres about 4 px", pool, POOL_PARTICLES, &small, RADIUS);
    /* Spheres about a texel across in the shadow map's thickness: that splat rides along too. */
    bool sun = check_same_fused(&f, "pool, spheres about 2 px", pool, POOL_PARTICLES, &small, 0.45f * RADIUS);
    CHECK_MSG(sun, "the shadow map's thickness of spheres about a texel across was splatted apart");
    check_same_fused(&f, "cloud", cloud, CLOUD_PARTICLES, &axis, 0.01f);
    free(pool);
    free(cloud);
    fixture_close(&f);
    return test_result();
}
