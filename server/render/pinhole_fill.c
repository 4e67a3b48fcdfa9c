/* pinhole_fill.c — see pinhole_fill.h. */
#include "pinhole_fill.h"

#include <limits.h>
#include <math.h>

/* Uniform locations fixed by layout(location) in pinhole_fill.glsl. */
enum { LOC_FILL_REACH_DEPTH = 50, LOC_FILL_MAX_STEP = 51, LOC_FILL_STEPS = 53, LOC_FILL_STRIDE = 55 };

/* Fluid must lie within this many projected radii on each side of a gap:
 * gaps up to one and a half radii across close, wider ones are real. */
#define REACH_RADII 0.75f
/* The two sides of a gap lie on one surface when their depths differ by
 * less than this many radii (the smoothing's own test of one surface). */
#define STEP_RADII 4.0f
/* max_reach and dense_steps of pinhole_fill.glsl: the most steps a walk
 * takes, and how many of them are one texel long. */
#define MAX_STEPS 12
#define DENSE_STEPS 6
/* Both splats keep only depths behind the near plane (ndc z >= -1), which
 * float rounding may let through a hair in front of it. */
#define NEAR_SLACK 0.99

/* How far a walk needs to go: fluid found k texels away counts only if k <=
 * reach_depth / z, and no kept depth z lies in front of the near plane, so
 * no walk needs more than reach_depth / near texels. A walk costs its steps
 * (most background pixels take all of them, about 1 ms per step at 1024x768
 * on llvmpipe); frames of small sprites (1M particles at 1024x768: 2 steps,
 * the shadow map: 0-1) are spared the rest without a pixel changing. Frames
 * whose nearest sprites are larger (a close-up: spheres 19 pixels in radius
 * leave gaps wider than DENSE_STEPS texels) walk texel by texel for
 * DENSE_STEPS steps, then stride over several texels per step, so the fill
 * closes pinholes at any size with at most MAX_STEPS steps. */
typedef struct fill_walk {
    int steps;
    int stride;   /* texels per step past DENSE_STEPS */
} fill_walk;

static fill_walk walk_of(const fc_view *view, float reach_depth)
{
    double bound = (double)reach_depth / (NEAR_SLACK * (double)view->near_plane);
    int texels = bound >= (double)INT_MAX / 2 ? INT_MAX / 2 : (int)floor(bound + 1e-3);
    if (texels <= DENSE_STEPS)
        return (fill_walk){texels, 1};
    int far = texels - DENSE_STEPS, far_steps = MAX_STEPS - DENSE_STEPS;
    int stride = (far + far_steps - 1) / far_steps;
    return (fill_walk){DENSE_STEPS + far / stride, stride};
}

static int walk_texels(fill_walk walk)
{
    return walk.steps <= DENSE_STEPS ? walk.steps : DENSE_STEPS + (walk.steps - DENSE_STEPS) * walk.stride;
}

int fc_pinhole_fill_apply(GLuint program, const fc_view *view, float radius)
{
    /* A radius r at depth z spans r fy h / (2 z) pixels. */
    float reach_depth = REACH_RADII * radius * view->fy * 0.5f * (float)view->height;
    glProgramUniform1f(program, LOC_FILL_REACH_DEPTH, reach_depth);
    glProgramUniform1f(program, LOC_FILL_MAX_STEP, STEP_RADII * radius);
    fill_walk walk = walk_of(view, reach_depth);
    glProgramUniform1i(program, LOC_FILL_STEPS, walk.steps);
    glProgramUniform1i(program, LOC_FILL_STRIDE, walk.stride);
    return walk_texels(walk);
}
