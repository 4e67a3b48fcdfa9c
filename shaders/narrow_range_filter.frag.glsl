#version 450 core
// One 1-D pass of the narrow-range filter (Truong & Yuksel 2018, "A
// Narrow-Range Filter for Screen-Space Fluid Rendering"), in its separable
// form: a Gaussian over the neighbours whose depth lies in a narrow range
// around the centre.
//  - Neighbours nearer than the range belong to a surface in front: they get
//    no weight, and neither does their mirror image on the other side, so the
//    kernel stays symmetric and a slope is not biased (bias correction).
//  - Neighbours farther than the range (other surfaces, background) are
//    clamped to z + mu r: silhouettes bend away from the camera by at most
//    mu r instead of being dragged to the far surface or left sharp. With the
//    filter iterated, z is the pixel's unfiltered depth, carried along in the
//    second channel, so the bound holds for any number of passes.
//  - Each side's range follows accepted neighbours (dynamic range), so a
//    steep but continuous surface is not mistaken for a discontinuity.
// Depth grows away from the camera here, the opposite of the paper's view z.

bool on_grid(ivec2 p);
vec4 texel_at(ivec2 p);
float depth_at(ivec2 p);
int kernel_radius(float z);

layout(location = 0) uniform ivec2 axis;
layout(location = 2) uniform float particle_radius;
layout(location = 3) uniform float depth_jump;   // the paper's threshold, half-width of the range: the pipeline's depth jump

layout(location = 0) out vec2 result;   // filtered depth, unfiltered depth

// The paper's clamping ratio mu: far neighbours count as this many radii behind the centre.
const float CLAMP_RADII = 1.0;

struct depth_range {
    float nearest;
    float farthest;
};

const int ACCEPTED = 0;
const int IN_FRONT = 1;   // nearer than the range: no weight
const int BEHIND = 2;     // farther than the range, or background: clamped
const int OFF_GRID = 3;

int classify(ivec2 q, depth_range range, out float zq)
{
    zq = depth_at(q);
    if (!on_grid(q))
        return OFF_GRID;
    if (zq <= 0.0 || zq > range.farthest)
        return BEHIND;
    if (zq < range.nearest)
        return IN_FRONT;
    return ACCEPTED;
}

depth_range extended(depth_range range, float zq)
{
    return depth_range(min(range.nearest, zq - depth_jump), max(range.farthest, zq + depth_jump));
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 centre = texel_at(p).rg;
    float z = centre.r;
    // The first pass reads raw depth, whose second channel is 0.
    float unfiltered = centre.g > 0.0 ? centre.g : z;
    if (z <= 0.0) {
        result = vec2(z, unfiltered);
        return;
    }
    int radius = kernel_radius(z);
    float sigma = float(radius) / 3.0;   // the kernel ends at three sigmas
    float inv_two_sigma2 = 0.5 / (sigma * sigma);
    float clamped = unfiltered + CLAMP_RADII * particle_radius;

    depth_range forward = depth_range(z - depth_jump, z + depth_jump);
    depth_range backward = forward;
    float sum = z, weight_sum = 1.0;
    for (int i = 1; i <= radius; i++) {
        float z_fwd, z_bwd;
        int fwd = classify(p + i * axis, forward, z_fwd);
        int bwd = classify(p - i * axis, backward, z_bwd);
        if (fwd == ACCEPTED)
            forward = extended(forward, z_fwd);
        if (bwd == ACCEPTED)
            backward = extended(backward, z_bwd);
        if (fwd == IN_FRONT || bwd == IN_FRONT || fwd == OFF_GRID || bwd == OFF_GRID)
            continue;
        float w = exp(-float(i * i) * inv_two_sigma2);
        sum += w * ((fwd == BEHIND ? clamped : z_fwd) + (bwd == BEHIND ? clamped : z_bwd));
        weight_sum += 2.0 * w;
    }
    result = vec2(sum / weight_sum, unfiltered);
}
