/* test_fill_candidates.c — the compute splat runs the pinhole fill's walks
 * only in the tiles fill_candidates.comp.glsl lists (fc_compute_splat's
 * fill_candidates: pinhole_fill.comp.glsl after the resolve's draw). The
 * list may only change the work, never the image: with it and with the
 * walks at every empty pixel (the resolve's draw with the fill) the depth (the depth alone) and the
 * colour (the thickness splatted with the depth, or at a reduced scale in
 * the culled depth's walk) are the same bit for bit, on a jittered sheet of
 * spheres whose holes the fill closes, seen from two distances (walks of 6
 * and 4 texels) at several sub-tile offsets. The sheet is checked to test
 * what the list relies on: filled pixels in tiles without any splatted
 * depth (a test of the tile alone would miss them) and filled pixels whose
 * nearest fluid along an axis lies reach_tiles tiles away, at the edge of
 * the walk. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline_internal.h"
#include "render_fixture.h"
#include "test_util.h"

#define WIDTH 320
#define HEIGHT 240
#define TILE_PX 4   /* CULL_TILE_PX in compute_splat.c */
#define SIDE_X 15
#define SIDE_Y 11
#define COUNT (SIDE_X * SIDE_Y)
/* About 20 px apart at the camera's distance 1, 0.55 spacings in radius:
 * holes about a radius across between each four spheres, which the fill
 * closes with walks of up to 6 texels (fill_steps 6, reach_tiles 2). */
#define SPACING 0.06f
#define RADIUS (0.55f * SPACING)

static float jitter(uint32_t *state, float amplitude)
{
    *state = *state * 1664525u + 1013904223u;
    return ((float)(*state >> 8) / 16777216.0f - 0.5f) * 2.0f * amplitude;
}

static void jittered_sheet(float *x)
{
    uint32_t state = 777u;
    for (int j = 0, n = 0; j < SIDE_Y; j++)
        for (int i = 0; i < SIDE_X; i++, n++) {
            x[3 * n] = ((float)i - 0.5f * (SIDE_X - 1)) * SPACING + jitter(&state, 0.2f * SPACING);
            x[3 * n + 1] = ((float)j - 0.5f * (SIDE_Y - 1)) * SPACING + jitter(&state, 0.2f * SPACING);
            x[3 * n + 2] = jitter(&state, 0.2f * SPACING);
        }
}

/* The compute splat's raw depth of the last run (+inf bits where nothing
 * was splatted), rows top-down as fc_image's. */
static uint32_t *read_splatted(render_fixture *f)
{
    fc_compute_splat *splat = fc_pipeline_compute_splat(f->pipeline);
    uint32_t *up = malloc((size_t)WIDTH * HEIGHT * sizeof *up), *down = malloc((size_t)WIDTH * HEIGHT * sizeof *down);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureSubImage(splat->nearest_depth, 0, 0, 0, 0, WIDTH, HEIGHT, 1, GL_RED_INTEGER, GL_UNSIGNED_INT,
                         (GLsizei)((size_t)WIDTH * HEIGHT * sizeof *up), up);
    CHECK(glGetError() == GL_NO_ERROR);
    for (int row = 0; row < HEIGHT; row++)
        memcpy(&down[(size_t)row * WIDTH], &up[(size_t)(HEIGHT - 1 - row) * WIDTH], WIDTH * sizeof *up);
    free(up);
    return down;
}

static bool splatted(const uint32_t *raw, int x, int row)
{
    return x >= 0 && row >= 0 && x < WIDTH && row < HEIGHT && raw[(size_t)row * WIDTH + x] != 0x7f800000u;
}

/* How the filled pixels (depth, none splatted) exercise the list: those
 * in tiles without a splatted depth, and those whose nearest fluid along one
 * axis direction lies reach_tiles tiles from their own. */
typedef struct fill_reach {
    int filled, in_empty_tiles, at_reach;
} fill_reach;

static bool tile_empty(const uint32_t *raw, int tx, int ty)
{
    for (int row = ty * TILE_PX; row < (ty + 1) * TILE_PX; row++)
        for (int x = tx * TILE_PX; x < (tx + 1) * TILE_PX; x++)
            if (splatted(raw, x, row))
                return false;
    return true;
}

static fill_reach measure_reach(const fc_image *depth, const uint32_t *raw, int steps)
{
    const int dirs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    int reach_tiles = (steps + TILE_PX - 1) / TILE_PX;
    fill_reach out = {0};
    for (int row = 0; row < HEIGHT; row++)
        for (int x = 0; x < WIDTH; x++) {
            if (splatted(raw, x, row) || pixel_f32(depth, (uint32_t)x, (uint32_t)row) == 0.0f)
                continue;
            out.filled++;
            out.in_empty_tiles += tile_empty(raw, x / TILE_PX, row / TILE_PX);
            bool at_reach = false;
            for (int d = 0; d < 4; d++)
                for (int k = 1; k <= steps; k++)
                    if (splatted(raw, x + k * dirs[d][0], row + k * dirs[d][1])) {
                        int tiles = abs((x + k * dirs[d][0]) / TILE_PX - x / TILE_PX) +
                                    abs((row + k * dirs[d][1]) / TILE_PX - row / TILE_PX);
                        at_reach = at_reach || tiles == reach_tiles;
                        break;
                    }
            out.at_reach += at_reach;
        }
    return out;
}

/* The depth alone (FC_SPLAT_DEPTH_ONLY) with and without the candidates:
 * the same bits; returns how the fill reached. */
static fill_reach check_depth(render_fixture *f, const float *x, const fc_camera *cam, int *steps)
{
    fc_compute_splat *splat = fc_pipeline_compute_splat(f->pipeline);
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    fc_image marked = {0}, all = {0};
    splat->fill_candidates = false;
    CHECK_CODE(render_positions(f, x, COUNT, cam, &settings, FC_AOV_DEPTH, 0, &all), FC_OK);
    splat->fill_candidates = true;
    CHECK_CODE(render_positions(f, x, COUNT, cam, &settings, FC_AOV_DEPTH, 0, &marked), FC_OK);
    CHECK(fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_COMPUTE);
    glGetUniformiv(splat->fill_program, 53, steps);   /* fill_steps, pinhole_fill.glsl */
    uint32_t *raw = read_splatted(f);
    int differ = 0;
    for (uint32_t row = 0; row < HEIGHT; row++)
        for (uint32_t px = 0; px < WIDTH; px++)
            differ += pixel_f32(&marked, px, row) != pixel_f32(&all, px, row);
    fill_reach reach = measure_reach(&all, raw, *steps);
    CHECK_MSG(differ == 0, "depth: %d pixels differ with the fill candidates (%d filled)", differ, reach.filled);
    free(raw);
    fc_image_free(&marked);
    fc_image_free(&all);
    return reach;
}

/* The colour with the candidates, and without them (and, at a reduced
 * thickness scale, with the thickness splatted apart, which
 * test_splat_culling.c shows gives the same bits as fused): the same bits.
 * Thickness at full scale: splatted with the depth
 * (FC_SPLAT_DEPTH_AND_THICKNESS); at a reduced scale, for small spheres: in
 * the culled depth's walk (fc_compute_splat_run_fused). Before the run with
 * the candidates, a run of one particle leaves its tiles, which the colour's
 * must not use. */
static void check_colour(render_fixture *f, const float *x, const fc_camera *cam, float thickness_scale)
{
    fc_compute_splat *splat = fc_pipeline_compute_splat(f->pipeline);
    fc_settings settings = test_settings(RADIUS, FC_SMOOTHING_NONE, 0);
    settings.thickness_scale = thickness_scale;
    fc_image marked = {0}, all = {0}, other = {0};
    splat->fill_candidates = splat->fuse = false;
    CHECK_CODE(render_positions(f, x, COUNT, cam, &settings, FC_AOV_COLOR, 0, &all), FC_OK);
    splat->fill_candidates = splat->fuse = true;
    CHECK_CODE(render_positions(f, x, 1, cam, &settings, FC_AOV_DEPTH, 0, &other), FC_OK);
    CHECK_CODE(render_positions(f, x, COUNT, cam, &settings, FC_AOV_COLOR, 0, &marked), FC_OK);
    CHECK(fc_pipeline_last_splat(f->pipeline) == FC_SPLAT_COMPUTE);
    CHECK_MSG(splat->last_fused == (thickness_scale < 1.0f), "thickness scale %g: fused %d", thickness_scale,
              splat->last_fused);
    size_t bytes = (size_t)WIDTH * HEIGHT * marked.channels * sizeof(float);
    CHECK_MSG(marked.width == all.width && marked.channels == all.channels &&
                  memcmp(marked.pixels, all.pixels, bytes) == 0,
              "colour (thickness scale %g) differs with the fill candidates", thickness_scale);
    fc_image_free(&marked);
    fc_image_free(&all);
    fc_image_free(&other);
}

/* The sheet from `distance`, the camera moved by fractions of a tile so that
 * the holes straddle tile edges at every phase. */
static fill_reach check_view(render_fixture *f, const float *x, double distance, float thickness_scale,
                             int *reach_tiles)
{
    fill_reach total = {0};
    for (int shift = 0; shift < 4; shift++) {
        fc_camera cam = axis_camera(distance, WIDTH, HEIGHT);
        float pixel = (float)distance * SPACING / 20.0f;   /* about a pixel at the sheet */
        float dx = 0.3f * (float)shift * pixel, dy = 0.7f * (float)shift * pixel;
        cam.eye[0] += dx, cam.target[0] += dx, cam.eye[1] += dy, cam.target[1] += dy;
        int steps = 0;
        fill_reach r = check_depth(f, x, &cam, &steps);
        check_colour(f, x, &cam, thickness_scale);
        CHECK_MSG(steps >= 3, "fill_steps %d at distance %g: too short to reach other tiles", steps, distance);
        *reach_tiles = (steps + TILE_PX - 1) / TILE_PX;
        printf("distance %g, shift %d: fill_steps %d, %d pixels filled, %d of them in tiles without fluid, %d with "
               "fluid %d tiles away\n",
               distance, shift, steps, r.filled, r.in_empty_tiles, r.at_reach, *reach_tiles);
        total.filled += r.filled, total.in_empty_tiles += r.in_empty_tiles, total.at_reach += r.at_reach;
    }
    return total;
}

int main(int argc, char **argv)
{
    render_fixture f;
    if (!fixture_open_splat(&f, argc, argv))
        return 1;
    fc_pipeline_force_splat(f.pipeline, FC_SPLAT_COMPUTE);
    float x[3 * COUNT];
    jittered_sheet(x);
    /* Spheres about 22 px across: walks of 6 texels, two tiles' reach; holes that hold whole empty tiles. */
    int reach_tiles = 0;
    fill_reach near = check_view(&f, x, 1.0, 1.0f, &reach_tiles);
    CHECK(reach_tiles == 2);
    CHECK_MSG(near.filled > 2000, "only %d pixels filled", near.filled);
    CHECK_MSG(near.in_empty_tiles > 20, "only %d filled pixels in tiles without fluid", near.in_empty_tiles);
    CHECK_MSG(near.at_reach > 20, "only %d filled pixels with fluid at the reach", near.at_reach);
    /* About 11 px across: walks of 4, one tile's reach; the thickness at a quarter fused with the depth. */
    fill_reach far = check_view(&f, x, 2.0, 0.25f, &reach_tiles);
    CHECK(reach_tiles == 1);
    CHECK_MSG(far.filled > 200 && far.at_reach > 20, "far: %d pixels filled, %d with fluid at the reach", far.filled,
              far.at_reach);
    fixture_close(&f);
    return test_result();
}
