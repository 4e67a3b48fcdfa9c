/* pinhole_fill.c — see pinhole_fill.h. */
#include "pinhole_fill.h"

#include <math.h>

/* Uniform locations fixed by layout(location) in pinhole_fill.glsl. */
enum { LOC_FILL_REACH_DEPTH = 50, LOC_FILL_MAX_STEP = 51, LOC_FILL_STEPS = 53 };

/* Fluid must lie within this many projected radii on each side of a gap:
 * gaps up to one and a half radii across close, wider ones are real. */
#define REACH_RADII 0.75f
/* The two sides of a gap lie on one surface when their depths differ by
 * less than this many radii (the smoothing's own test of one surface). */
#define STEP_RADII 4.0f
/* max_reach of pinhole_fill.glsl: the most texels a walk takes. */
#define MAX_STEPS 6
/* Both splats keep only depths behind the near plane (ndc z >= -1), which
 * float rounding may let through a hair in front of it. */
#define NEAR_SLACK 0.99

/* How far a walk needs to go: fluid found k texels away counts only if k <=
 * reach_depth / z, and no kept depth z lies in front of the near plane, so
 * no walk needs more than reach_depth / near steps. A walk costs its steps
 * (most background pixels take all of them, about 1 ms per step at 1024x768
 * on llvmpipe); frames of small sprites (1M particles at 1024x768: 2 steps,
 * the shadow map: 0-1) are spared the rest without a pixel changing. */
static int walk_steps(const fc_view *view, float reach_depth)
{
    double bound = (double)reach_depth / (NEAR_SLACK * (double)view->near_plane);
    return bound >= MAX_STEPS ? MAX_STEPS : (int)floor(bound + 1e-3);
}

int fc_pinhole_fill_apply(GLuint program, const fc_view *view, float radius)
{
    /* A radius r at depth z spans r fy h / (2 z) pixels. */
    float reach_depth = REACH_RADII * radius * view->fy * 0.5f * (float)view->height;
    glProgramUniform1f(program, LOC_FILL_REACH_DEPTH, reach_depth);
    glProgramUniform1f(program, LOC_FILL_MAX_STEP, STEP_RADII * radius);
    int steps = walk_steps(view, reach_depth);
    glProgramUniform1i(program, LOC_FILL_STEPS, steps);
    return steps;
}
