/* sloshing_block.c — see sloshing_block.h. */
#include "sloshing_block.h"

#include <math.h>

#include "fc_frame.h"

#define SPACING 0.05f
#define COLUMNS_Y 20                   /* the tank is 1 deep: 20 columns of 0.05 */
#define MEAN_DEPTH 0.5f
#define AMPLITUDE 0.2f
#define MAX_LAYERS 20                  /* for ids: more than the deepest column holds */
#define TWO_PI 6.2831853f

/* Height of the surface at x: a plane through the tank's centre line, tilting. */
static float surface(float x, float phase)
{
    float half = SLOSH_TANK_LENGTH / 2.0f;
    return MEAN_DEPTH + AMPLITUDE * sinf(phase) * (x - half) / half;
}

/* Vertical velocity of a particle at height z in the column at x: the column
 * stretches uniformly as its surface moves. */
static float rise_speed(float x, float z, float phase)
{
    float half = SLOSH_TANK_LENGTH / 2.0f;
    float surface_speed = AMPLITUDE * cosf(phase) * (TWO_PI / SLOSH_PERIOD_FRAMES) * (x - half) / half;
    return surface_speed * z / surface(x, phase);
}

/* Visits every particle of the slab; returns how many there are. */
static uint64_t fill(uint32_t step, float x_begin, float x_end, fc_frame *frame)
{
    float phase = TWO_PI * (float)step / SLOSH_PERIOD_FRAMES;
    int columns_x = (int)(SLOSH_TANK_LENGTH / SPACING);
    uint64_t n = 0;
    for (int i = 0; i < columns_x; i++) {
        float x = (i + 0.5f) * SPACING;
        if (x < x_begin || x >= x_end)
            continue;
        int layers = (int)(surface(x, phase) / SPACING);
        for (int j = 0; j < COLUMNS_Y; j++)
            for (int k = 0; k < layers && k < MAX_LAYERS; k++, n++) {
                if (!frame)
                    continue;
                float z = (k + 0.5f) * SPACING;
                float *p = frame->positions + 3 * n;
                float *v = frame->velocity + 3 * n;
                p[0] = x;
                p[1] = (j + 0.5f) * SPACING;
                p[2] = z;
                v[0] = v[1] = 0.0f;
                v[2] = rise_speed(x, z, phase);
                frame->ids[n] = (uint32_t)((i * COLUMNS_Y + j) * MAX_LAYERS + k);
            }
    }
    return n;
}

fc_code slosh_frame(uint32_t step, float x_begin, float x_end, fc_frame *out, fc_error *err)
{
    fc_code code = fc_frame_alloc(out, fill(step, x_begin, x_end, NULL), FC_ATTR_VELOCITY | FC_ATTR_IDS, err);
    if (code == FC_OK)
        fill(step, x_begin, x_end, out);
    return code;
}
