/* test_smoothing_scale.c — the steps of reduced-resolution smoothing (van der
 * Laan et al. 2009, §3.5.1) one by one, through the real passes:
 *   down: every texel holds the nearest fluid depth of its block, so a line
 *   one pixel wide in front of a surface survives;
 *   up: inside a surface depth is the bilinear interpolation of the texels,
 *   and between surfaces each pixel keeps to its own unsmoothed surface;
 *   colour: pixels whose texels straddle a silhouette get the bilinear blend
 *   of the colours shaded at those texels' centres, the others keep theirs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render_fixture.h"
#include "smoothing_fixture.h"
#include "test_util.h"

#define BLOCK 2
#define LOW_W (SF_W / BLOCK)
#define LOW_H (SF_H / BLOCK)

static void test_down_keeps_nearest(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], low[LOW_W * LOW_H];
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++) {
            float z = 6.0f + 0.01f * x;
            z = x == 37 ? 5.0f : z;                     /* a thin sheet in front */
            z = x > 100 || (y > 70 && x > 80) ? 0.0f : z;   /* background, with a ragged edge */
            scene[y * SF_W + x] = y == 20 && x > 100 ? 7.0f : z;   /* a fluid row inside the background */
        }
    glTextureSubImage2D(sf->input.color, 0, 0, 0, SF_W, SF_H, GL_RED, GL_FLOAT, scene);
    const fc_render_target *target = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_resolution_scale_down(&sf->smoother.resolution, &sf->input, BLOCK, &target, &err), FC_OK);
    CHECK(target->width == LOW_W && target->height == LOW_H);
    CHECK_CODE(smoothing_read(target, low), FC_OK);
    int wrong = 0;
    for (int ty = 0; ty < LOW_H; ty++)
        for (int tx = 0; tx < LOW_W; tx++) {
            float nearest = 0.0f;
            for (int i = 0; i < BLOCK * BLOCK; i++) {
                float z = scene[(ty * BLOCK + i / BLOCK) * SF_W + tx * BLOCK + i % BLOCK];
                if (z > 0.0f && (nearest == 0.0f || z < nearest))
                    nearest = z;
            }
            wrong += low[ty * LOW_W + tx] != nearest;
        }
    CHECK_MSG(wrong == 0, "%d texels differ from the nearest depth of their block", wrong);
    CHECK(low[10 * LOW_W + 18] == 5.0f);   /* the sheet at x = 37 */
}

/* Uploads the unsmoothed full-resolution depth `full` and a smoothed
 * LOW_W x LOW_H depth image `low` into the resolution stage's targets. */
static const fc_render_target *upload(smoothing_fixture *sf, const float *full, const float *low)
{
    const fc_render_target *target = NULL;
    fc_error err = {0};
    glTextureSubImage2D(sf->input.color, 0, 0, 0, SF_W, SF_H, GL_RED, GL_FLOAT, full);
    if (fc_resolution_scale_down(&sf->smoother.resolution, &sf->input, BLOCK, &target, &err) != FC_OK)
        return NULL;
    glTextureSubImage2D(target->color, 0, 0, 0, LOW_W, LOW_H, GL_RED, GL_FLOAT, low);
    return target;
}

/* Runs the upsampling of `low` guided by `full` into `out`. */
static fc_code upsample(smoothing_fixture *sf, const float *full, const float *low, float *out)
{
    const fc_render_target *target = upload(sf, full, low), *result = NULL;
    fc_error err = {0};
    fc_code code = fc_resolution_scale_up(&sf->smoother.resolution, target, &sf->input, BLOCK, SF_DEPTH_JUMP,
                                          &result, &err);
    if (code == FC_OK && (result->width != SF_W || result->height != SF_H))
        code = FC_ERR_INTERNAL;
    return code == FC_OK ? smoothing_read(result, out) : code;
}

static double low_at(const float *low, int tx, int ty)
{
    tx = tx < 0 ? 0 : tx >= LOW_W ? LOW_W - 1 : tx;
    ty = ty < 0 ? 0 : ty >= LOW_H ? LOW_H - 1 : ty;
    return low[ty * LOW_W + tx];
}

/* Bilinear interpolation with texel centres at (t + 0.5) * BLOCK image pixels. */
static double bilinear(const float *low, int x, int y)
{
    double u = (x + 0.5) / BLOCK - 0.5, v = (y + 0.5) / BLOCK - 0.5;
    int tx = (int)floor(u), ty = (int)floor(v);
    double fx = u - tx, fy = v - ty;
    return (1 - fx) * (1 - fy) * low_at(low, tx, ty) + fx * (1 - fy) * low_at(low, tx + 1, ty) +
           (1 - fx) * fy * low_at(low, tx, ty + 1) + fx * fy * low_at(low, tx + 1, ty + 1);
}

static void test_up_interpolates(smoothing_fixture *sf)
{
    static float full[SF_PIXELS], low[LOW_W * LOW_H], out[SF_PIXELS];
    scene_plane(full, 5.0f);
    for (int ty = 0; ty < LOW_H; ty++)
        for (int tx = 0; tx < LOW_W; tx++)
            low[ty * LOW_W + tx] = 5.0f + 0.3f * sinf(0.2f * tx) * cosf(0.3f * ty);
    CHECK_CODE(upsample(sf, full, low, out), FC_OK);
    double worst = 0.0;
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            worst = fmax(worst, fabs(out[y * SF_W + x] - bilinear(low, x, y)));
    CHECK_MSG(worst < 1e-5, "upsampled depth is off the bilinear interpolation by up to %g", worst);
}

/* Texels hold a near surface left of column 32 and a far one right of it;
 * at full resolution the far surface starts one pixel earlier, at x = 63,
 * where the texels' weights would give the near one. */
static void test_up_follows_full_resolution_outline(smoothing_fixture *sf)
{
    static float full[SF_PIXELS], low[LOW_W * LOW_H], out[SF_PIXELS];
    for (int i = 0; i < SF_PIXELS; i++)
        full[i] = i % SF_W < 63 ? 5.0f : 6.0f;
    for (int i = 0; i < LOW_W * LOW_H; i++)
        low[i] = i % LOW_W < 32 ? 5.0f : 6.0f;
    CHECK_CODE(upsample(sf, full, low, out), FC_OK);
    int wrong = 0;
    for (int i = 0; i < SF_PIXELS; i++)
        wrong += out[i] != full[i];
    CHECK_MSG(wrong == 0, "%d pixels are not on their own surface", wrong);
}

static fc_code read_rgba(const fc_render_target *target, float *rgba)
{
    fc_error err = {0};
    fc_image img = {0};
    fc_code code = read_target(target, 4, &img, &err);
    if (code == FC_OK)
        for (uint32_t row = 0; row < img.height; row++)   /* back to GL order */
            memcpy(rgba + 4 * (size_t)(img.height - 1 - row) * img.width,
                   (const float *)img.pixels + 4 * (size_t)row * img.width, 4 * img.width * sizeof(float));
    fc_image_free(&img);
    return code;
}

/* Fluid (red) left of texel column 32, background (blue) right of it; the
 * "shaded" image is split at the same place, x = 64, and its green alternates
 * between 0 and 1 from column to column, so the texels' colours, the means
 * over their blocks, have green 0.5. */
static void test_colour_blend(smoothing_fixture *sf)
{
    static float low[LOW_W * LOW_H], shaded[4 * SF_PIXELS], out[4 * SF_PIXELS];
    for (int i = 0; i < LOW_W * LOW_H; i++)
        low[i] = i % LOW_W < 32 ? 5.0f : 0.0f;
    for (int i = 0; i < SF_PIXELS; i++) {
        bool fluid = i % SF_W < 64;
        const float colour[4] = {fluid ? 1.0f : 0.0f, (float)(i % 2), fluid ? 0.0f : 1.0f, 1.0f};
        memcpy(shaded + 4 * i, colour, sizeof colour);
    }
    fc_render_target shaded_target = fc_render_target_init(GL_RGBA32F, false, false);
    fc_error err = {0};
    static float full[SF_PIXELS];
    for (int i = 0; i < SF_PIXELS; i++)
        full[i] = i % SF_W < 64 ? 5.0f : 0.0f;
    const fc_render_target *low_target = upload(sf, full, low), *result = NULL;
    CHECK_CODE(fc_render_target_resize(&shaded_target, SF_W, SF_H, &err), FC_OK);
    glTextureSubImage2D(shaded_target.color, 0, 0, 0, SF_W, SF_H, GL_RGBA, GL_FLOAT, shaded);
    CHECK_CODE(fc_silhouette_blend_run(&sf->smoother.silhouette_blend, &shaded_target, low_target, BLOCK,
                                       SF_DEPTH_JUMP, false, &result, &err),
               FC_OK);
    CHECK_CODE(read_rgba(result, out), FC_OK);
    int wrong = 0;
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++) {
            /* Pixels 63 and 64 lie between the centres of texels 31 and 32,
             * which straddle the silhouette. */
            double u = (x + 0.5) / BLOCK - 0.5;
            bool straddles = x == 63 || x == 64;
            double fluid_weight = straddles ? 32.0 - u : x < 64;
            double expected[4] = {fluid_weight, straddles ? 0.5 : x % 2, 1.0 - fluid_weight, 1.0};
            for (int c = 0; c < 4; c++)
                wrong += fabs(out[4 * (y * SF_W + x) + c] - expected[c]) > 1e-6;
        }
    CHECK_MSG(wrong == 0, "%d colour components differ from the expected blend", wrong);
    CHECK_NEAR(out[4 * (10 * SF_W + 63)], 0.75, 1e-6);
    fc_render_target_release(&shaded_target);
}

int main(void)
{
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    test_down_keeps_nearest(&sf);
    test_up_interpolates(&sf);
    test_up_follows_full_resolution_outline(&sf);
    test_colour_blend(&sf);
    smoothing_close(&sf);
    return test_result();
}
