/* pinhole_fill.c — see pinhole_fill.h. */
#include "pinhole_fill.h"

/* Uniform locations fixed by layout(location) in pinhole_fill.glsl. */
enum { LOC_FILL_REACH_DEPTH = 50, LOC_FILL_MAX_STEP = 51 };

/* Fluid must lie within this many projected radii on each side of a gap:
 * gaps up to one and a half radii across close, wider ones are real. */
#define REACH_RADII 0.75f
/* The two sides of a gap lie on one surface when their depths differ by
 * less than this many radii (the smoothing's own test of one surface). */
#define STEP_RADII 4.0f

void fc_pinhole_fill_apply(GLuint program, const fc_view *view, float radius)
{
    /* A radius r at depth z spans r fy h / (2 z) pixels. */
    float reach_depth = REACH_RADII * radius * view->fy * 0.5f * (float)view->height;
    glProgramUniform1f(program, LOC_FILL_REACH_DEPTH, reach_depth);
    glProgramUniform1f(program, LOC_FILL_MAX_STEP, STEP_RADII * radius);
}
