/* test_ball.c — see test_ball.h. */
#include "test_ball.h"

#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"

static bool inside_ball(int i, int j, int k)
{
    return i * i + j * j + k * k <= BALL_STEPS * BALL_STEPS;
}

fc_code test_ball_frame(fc_frame *frame, fc_error *err)
{
    uint64_t count = 0;
    for (int i = -BALL_STEPS; i <= BALL_STEPS; i++)
        for (int j = -BALL_STEPS; j <= BALL_STEPS; j++)
            for (int k = -BALL_STEPS; k <= BALL_STEPS; k++)
                count += inside_ball(i, j, k);
    fc_code code = fc_frame_alloc(frame, count, 0, err);
    if (code != FC_OK)
        return code;
    float *p = frame->positions;
    for (int i = -BALL_STEPS; i <= BALL_STEPS; i++)
        for (int j = -BALL_STEPS; j <= BALL_STEPS; j++)
            for (int k = -BALL_STEPS; k <= BALL_STEPS; k++) {
                if (!inside_ball(i, j, k))
                    continue;
                *p++ = (float)i * BALL_SPACING;
                *p++ = (float)j * BALL_SPACING;
                *p++ = (float)k * BALL_SPACING;
            }
    return FC_OK;
}

fc_code test_ball_box_corners(fc_frame *frame, fc_error *err)
{
    fc_code code = fc_frame_alloc(frame, 8, 0, err);
    if (code != FC_OK)
        return code;
    for (int c = 0; c < 8; c++)
        for (int axis = 0; axis < 3; axis++)
            frame->positions[3 * c + axis] = (c >> axis) & 1 ? BALL_RADIUS : -BALL_RADIUS;
    return FC_OK;
}

void test_ball_camera(uint32_t width, uint32_t height, fc_camera *cam)
{
    *cam = (fc_camera){
        .eye = { 0.0f, -BALL_EYE_DISTANCE, 0.0f },
        .target = { 0.0f, 0.0f, 0.0f },
        .up = { 0.0f, 0.0f, 1.0f },
        .fov_y_deg = BALL_FOV_DEG,
        .width = width,
        .height = height,
    };
}

static void put_le32(uint8_t out[4], float value)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 4; i++)
        out[i] = (uint8_t)(bits >> (8 * i));
}

bool test_write_f32(const fc_frame *frame, const char *path)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    bool ok = true;
    for (uint64_t i = 0; i < 3 * frame->count && ok; i++) {
        uint8_t bytes[4];
        put_le32(bytes, frame->positions[i]);
        ok = fwrite(bytes, 1, sizeof bytes, f) == sizeof bytes;
    }
    return fclose(f) == 0 && ok;
}

bool test_write_ply(const fc_frame *frame, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    bool ok = fprintf(f, "ply\nformat ascii 1.0\nelement vertex %llu\n"
                         "property float x\nproperty float y\nproperty float z\nend_header\n",
                      (unsigned long long)frame->count) > 0;
    for (uint64_t i = 0; i < frame->count && ok; i++) {
        const float *p = frame->positions + 3 * i;
        ok = fprintf(f, "%.9g %.9g %.9g\n", (double)p[0], (double)p[1], (double)p[2]) > 0;
    }
    return fclose(f) == 0 && ok;
}
