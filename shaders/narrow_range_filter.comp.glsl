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
//
// A compute shader, so that one invocation can filter RUN consecutive pixels
// along the axis: their kernels overlap, and sliding the run's window one
// step outward per tap needs two texel fetches for all RUN pixels, where a
// fragment shader (one pixel each) fetched two per pixel. Fetches dominate
// on a software rasterizer: the filter runs 1.5-1.9x faster on llvmpipe
// (bench/RESULTS.md). Each pixel's arithmetic is the fragment version's, and
// so are the results, bit for bit.
// (A workgroup tile in shared memory was measured too, and was 2-3x slower
// than the fragment shader on llvmpipe, where every shared-memory load is a
// loop over the SIMD lanes.)

vec4 texel_at(ivec2 p);
int kernel_radius(float z);

layout(binding = 0) uniform sampler2D depth_in;
layout(location = 0) uniform ivec2 axis;
layout(location = 2) uniform float particle_radius;
layout(location = 3) uniform float depth_jump;   // the paper's threshold, half-width of the range: the pipeline's depth jump
layout(location = 40) uniform ivec2 source_size;   // the image in use; the texture may be larger (stale texels)

layout(binding = 0, rg32f) uniform writeonly image2D filtered;   // filtered depth, unfiltered depth
// False once the image written holds this run's background already (the
// third pass on, separable_filter.c): background pixels (depth 0) come out
// as exactly (0, 0) in every pass, so only the fluid is stored. llvmpipe
// stores an image lane by lane, a third of the filter's time; 60% of a
// typical image is background.
uniform bool store_background;

// Invocations are laid out over the image, each one RUN pixels long along the axis.
layout(local_size_x = 8, local_size_y = 8) in;
#define RUN 8

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

// One pixel of the run while its kernel is being summed.
struct pixel_state {
    float z;
    float unfiltered;
    float clamped;
    float inv_two_sigma2;
    int radius;             // 0: background, nothing to sum
    depth_range forward;
    depth_range backward;
    float sum;
    float weight_sum;
};

// Depth at `along` on the run's line, 0 (background) off the grid.
float depth_along(ivec2 first, int start, int along, int length)
{
    return along >= 0 && along < length ? texel_at(first + (along - start) * axis).r : 0.0;
}

int classify(float zq, bool on_grid, depth_range range)
{
    if (!on_grid)
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

pixel_state start_pixel(vec2 centre)
{
    pixel_state s;
    s.z = centre.r;
    // The first pass reads raw depth, whose second channel is 0.
    s.unfiltered = centre.g > 0.0 ? centre.g : s.z;
    s.radius = s.z > 0.0 ? kernel_radius(s.z) : 0;
    float sigma = float(s.radius) / 3.0;   // the kernel ends at three sigmas
    s.inv_two_sigma2 = 0.5 / (sigma * sigma);
    s.clamped = s.unfiltered + CLAMP_RADII * particle_radius;
    s.forward = depth_range(s.z - depth_jump, s.z + depth_jump);
    s.backward = s.forward;
    s.sum = s.z;
    s.weight_sum = 1.0;
    return s;
}

// Tap i of a pixel's kernel: z_fwd, z_bwd are the depths i pixels ahead and behind.
void add_tap(inout pixel_state s, int i, float z_fwd, bool fwd_on_grid, float z_bwd, bool bwd_on_grid)
{
    if (i > s.radius)
        return;
    int fwd = classify(z_fwd, fwd_on_grid, s.forward);
    int bwd = classify(z_bwd, bwd_on_grid, s.backward);
    if (fwd == ACCEPTED)
        s.forward = extended(s.forward, z_fwd);
    if (bwd == ACCEPTED)
        s.backward = extended(s.backward, z_bwd);
    if (fwd == IN_FRONT || bwd == IN_FRONT || fwd == OFF_GRID || bwd == OFF_GRID)
        return;
    float w = exp(-float(i * i) * s.inv_two_sigma2);
    s.sum += w * ((fwd == BEHIND ? s.clamped : z_fwd) + (bwd == BEHIND ? s.clamped : z_bwd));
    s.weight_sum += 2.0 * w;
}

void main()
{
    ivec2 size = source_size;
    int length = axis.x != 0 ? size.x : size.y;
    ivec2 first = ivec2(gl_GlobalInvocationID.xy) * (ivec2(1) + (RUN - 1) * axis);
    if (any(greaterThanEqual(first, size)))
        return;
    int start = first.x * axis.x + first.y * axis.y;

    pixel_state pixel[RUN];
    float ahead[RUN], behind[RUN];   // the depths i pixels ahead of and behind each pixel of the run
    int taps = 0;
    for (int k = 0; k < RUN; k++) {
        vec2 centre = start + k < length ? texel_at(first + k * axis).rg : vec2(0.0);
        pixel[k] = start_pixel(centre);
        ahead[k] = behind[k] = centre.r;
        taps = max(taps, pixel[k].radius);
    }
    for (int i = 1; i <= taps; i++) {
        for (int k = 0; k < RUN - 1; k++)
            ahead[k] = ahead[k + 1];
        ahead[RUN - 1] = depth_along(first, start, start + RUN - 1 + i, length);
        for (int k = RUN - 1; k > 0; k--)
            behind[k] = behind[k - 1];
        behind[0] = depth_along(first, start, start - i, length);
        for (int k = 0; k < RUN; k++)
            add_tap(pixel[k], i, ahead[k], start + k + i < length, behind[k], start + k - i >= 0);
    }
    for (int k = 0; k < RUN && start + k < length; k++)
        if (store_background || pixel[k].z > 0.0)
            imageStore(filtered, first + k * axis,
                       vec4(pixel[k].sum / pixel[k].weight_sum, pixel[k].unfiltered, 0.0, 0.0));
}
