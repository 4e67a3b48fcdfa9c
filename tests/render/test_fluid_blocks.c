/* test_fluid_blocks.c — the list of 8x8 blocks that hold fluid, on which the
 * narrow-range filter runs (fluid_blocks.h): exactly the blocks with a texel
 * > 0 inside the image in use, each once, read back from the real buffer.
 * The image in use (61 x 45) is smaller than its texture, whose texels beyond
 * it hold stale fluid, so the partial blocks on the right and top edges count
 * only what lies inside; an image without fluid lists nothing and the filter
 * leaves it all background. */
#include <stdlib.h>
#include <string.h>

#include "fluid_blocks.h"
#include "smoothing_fixture.h"
#include "test_util.h"

#define USED_W 61
#define USED_H 45
#define COLUMNS ((USED_W + 7) / 8)
#define ROWS ((USED_H + 7) / 8)

/* Stale fluid beyond the image in use, background inside but for `marks` (x, y pairs). */
static void scene_marks(float *depth, const int (*marks)[2], int count)
{
    for (int y = 0; y < SF_H; y++)
        for (int x = 0; x < SF_W; x++)
            depth[y * SF_W + x] = x >= USED_W || y >= USED_H ? 7.0f : 0.0f;
    for (int i = 0; i < count; i++)
        depth[marks[i][1] * SF_W + marks[i][0]] = 5.0f + 0.01f * (float)i;
}

/* The blocks listed, as a COLUMNS x ROWS map of how often each appears; false when one lies outside. */
static bool listed_blocks(const fc_fluid_blocks *b, int *times, uint32_t *count)
{
    GLuint header[3] = {0, 0, 0};
    glGetNamedBufferSubData(b->buffer, 0, sizeof header, header);
    *count = header[0];
    CHECK_MSG(header[1] == 1 && header[2] == 1, "workgroup counts y, z: %u %u", header[1], header[2]);
    memset(times, 0, COLUMNS * ROWS * sizeof *times);
    if (header[0] > b->capacity)
        return false;
    GLuint *list = malloc((header[0] + 1) * sizeof *list);
    glGetNamedBufferSubData(b->buffer, 3 * sizeof(GLuint), header[0] * sizeof(GLuint), list);
    bool inside = true;
    for (uint32_t i = 0; i < header[0]; i++) {
        uint32_t column = list[i] & 0xffffu, row = list[i] >> 16;
        if (column >= COLUMNS || row >= ROWS)
            inside = false;
        else
            times[row * COLUMNS + column]++;
    }
    free(list);
    return inside;
}

static void test_list(smoothing_fixture *sf)
{
    /* Corners of the image, both sides of a block edge, the partial column (x 56..60) and row (y 40..44)
     * of blocks, and a block's far corner; the blocks of x 61..63 or y 45..47 hold only stale fluid. */
    static const int marks[][2] = {{0, 0},   {60, 44}, {60, 0},  {0, 44},  {7, 7},  {8, 8},  {15, 16},
                                   {56, 20}, {33, 40}, {23, 31}, {24, 31}, {47, 3}, {40, 12}};
    const int count = (int)(sizeof marks / sizeof marks[0]);
    static float scene[SF_PIXELS];
    scene_marks(scene, marks, count);
    glTextureSubImage2D(sf->input.color, 0, 0, 0, SF_W, SF_H, GL_RED, GL_FLOAT, scene);
    fc_error err = {0};
    CHECK_CODE(fc_render_target_resize(&sf->input, USED_W, USED_H, &err), FC_OK);
    fc_fluid_blocks blocks;
    CHECK_CODE(fc_fluid_blocks_create(NULL, &blocks, &err), FC_OK);
    CHECK_CODE(fc_fluid_blocks_find(&blocks, &sf->input, &err), FC_OK);
    CHECK_MSG(blocks.capacity >= COLUMNS * ROWS, "room for %u blocks", blocks.capacity);

    int expected[COLUMNS * ROWS] = {0}, times[COLUMNS * ROWS];
    uint32_t wanted = 0, listed = 0;
    for (int i = 0; i < count; i++) {
        int *e = &expected[marks[i][1] / 8 * COLUMNS + marks[i][0] / 8];
        wanted += *e == 0;
        *e = 1;
    }
    CHECK_MSG(listed_blocks(&blocks, times, &listed), "a block outside the image was listed");
    CHECK_MSG(listed == wanted, "%u blocks listed, %u hold fluid", listed, wanted);
    for (int i = 0; i < COLUMNS * ROWS; i++)
        CHECK_MSG(times[i] == expected[i], "block (%d, %d) listed %d times, holds fluid: %d", i % COLUMNS,
                  i / COLUMNS, times[i], expected[i]);

    /* No fluid in the image in use (only the stale texels): nothing listed. */
    scene_marks(scene, marks, 0);
    glTextureSubImage2D(sf->input.color, 0, 0, 0, SF_W, SF_H, GL_RED, GL_FLOAT, scene);
    CHECK_CODE(fc_fluid_blocks_find(&blocks, &sf->input, &err), FC_OK);
    CHECK(listed_blocks(&blocks, times, &listed));
    CHECK_MSG(listed == 0, "%u blocks listed for an image without fluid", listed);
    fc_fluid_blocks_destroy(&blocks);
    CHECK_CODE(fc_render_target_resize(&sf->input, SF_W, SF_H, &err), FC_OK);
}

/* Background everywhere: the narrow-range filter dispatches no block and its result is all 0. */
static void test_no_fluid(smoothing_fixture *sf)
{
    static float scene[SF_PIXELS], out[SF_PIXELS];
    /* A run with fluid first, so that both ping-pong targets hold depths the next run must clear. */
    scene_plane(scene, 5.0f);
    for (uint32_t radius = 0; radius <= 5; radius += 5) {
        fc_smoothing_params params = smoothing_params(FC_SMOOTHING_NARROW, 2, 1.0f);
        params.filter_radius = radius;
        scene_plane(scene, 5.0f);
        CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
        scene_plane(scene, 0.0f);
        CHECK_CODE(smoothing_apply(sf, scene, &params, out), FC_OK);
        int fluid = 0;
        for (int i = 0; i < SF_PIXELS; i++)
            fluid += out[i] != 0.0f;
        CHECK_MSG(fluid == 0, "filter radius %u: %d pixels not background after filtering none", radius, fluid);
    }
}

int main(void)
{
    smoothing_fixture sf;
    if (!smoothing_open(&sf))
        return 1;
    test_list(&sf);
    test_no_fluid(&sf);
    smoothing_close(&sf);
    return test_result();
}
