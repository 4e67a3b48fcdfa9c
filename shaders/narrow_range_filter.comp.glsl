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
//    filter iterated, z is the pixel's unfiltered depth, read from the
//    filter's input in every pass, so the bound holds for any number of passes.
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
//
// What llvmpipe (Mesa's software rasterizer) makes of it decides the rest
// (bench/RESULTS.md, "The narrow-range filter on the blocks that hold
// fluid"): both sides of every branch run, masked, and an early return skips
// nothing, so an invocation costs the same whether its pixels hold fluid or
// not; an image store is a loop over the 8 SIMD lanes per 32-bit word.
//  - Only the 8x8 blocks that hold fluid are dispatched (a list made once per
//    filter run, fluid_blocks.comp.glsl: the fluid's pixels are the same in
//    every pass), and only fluid pixels are stored: the targets are cleared
//    to 0 (background) first. One workgroup is one block, its 8 invocations
//    (one SIMD vector) the block's 8 lines across the axis.
//  - The output is R32F, one store loop per pixel: the unfiltered depth the
//    clamping needs is the filter's input (`unfiltered_depth`), so no pass
//    carries it along in a second channel.
//  - FC_FIXED_KERNEL (a program variant, chosen when the request fixes the
//    kernel half-width): every fluid pixel has the same kernel, so the
//    Gaussian weight of tap i is computed once per run instead of per pixel,
//    from the same operands and so to the same bits.

vec4 texel_at(ivec2 p);
int kernel_radius(float z);

layout(binding = 0) uniform sampler2D depth_in;           // the pass's input: the previous pass's output, or the raw depth
layout(binding = 1) uniform sampler2D unfiltered_depth;   // the filter's input (raw depth), for every pass
layout(location = 0) uniform ivec2 axis;
layout(location = 2) uniform float particle_radius;
layout(location = 3) uniform float depth_jump;   // the paper's threshold, half-width of the range: the pipeline's depth jump
layout(location = 40) uniform ivec2 source_size;   // the image in use; the texture may be larger (stale texels)

layout(binding = 0, r32f) uniform writeonly image2D filtered;   // background: cleared to 0 before the first pass

// The 8x8 blocks that hold fluid (fluid_blocks.comp.glsl): one workgroup per
// block, and background pixels (depth 0) elsewhere, which leave every pass
// as exactly 0, are neither read as a centre nor stored.
layout(std430, binding = 0) readonly buffer FluidBlocks {
    uint groups_x, groups_y, groups_z;
    uint blocks[];   // block column | block row << 16
};
#define BLOCK 8

// A workgroup is one block, its 8 invocations (one SIMD vector on llvmpipe)
// the block's 8 lines across the axis, each a run of RUN pixels along it.
layout(local_size_x = BLOCK) in;
#define RUN BLOCK

// The paper's clamping ratio mu: far neighbours count as this many radii behind the centre.
const float CLAMP_RADII = 1.0;

// The depth of a neighbour off the grid: never behind a range and always in
// front of it (ranges lie within a few depth jumps of the fluid's depths,
// far above this), so it takes the in-front case's part (no weight, for it
// and its mirror image; no extension), which is what the original
// classification gave a neighbour off the grid. Depths on the grid are never
// negative. (Finite: a constant infinity is not a constant expression to
// every GLSL compiler.)
const float OFF_GRID = -3.0e38;

struct depth_range {
    float nearest;
    float farthest;
};

// One pixel of the run while its kernel is being summed.
struct pixel_state {
    float z;
    float clamped;
#ifndef FC_FIXED_KERNEL
    float inv_two_sigma2;
    int radius;             // 0: background, nothing to sum
#endif
    depth_range forward;
    depth_range backward;
    float sum;
    float weight_sum;
};

// Depth at `along` on the run's line, OFF_GRID off it.
float depth_along(ivec2 first, int start, int along, int length)
{
    return along >= 0 && along < length ? texel_at(first + (along - start) * axis).r : OFF_GRID;
}

// Farther than the range, or background: clamped.
bool is_behind(float zq, depth_range range)
{
    return zq == 0.0 || zq > range.farthest;
}

// Nearer than the range (or off the grid): no weight.
bool is_in_front(float zq, bool behind, depth_range range)
{
    return !behind && zq < range.nearest;
}

depth_range extended(depth_range range, float zq)
{
    return depth_range(min(range.nearest, zq - depth_jump), max(range.farthest, zq + depth_jump));
}

float inv_two_sigma2_of(int radius)
{
    float sigma = float(radius) / 3.0;   // the kernel ends at three sigmas
    return 0.5 / (sigma * sigma);
}

pixel_state start_pixel(float z, float unfiltered)
{
    pixel_state s;
    s.z = z;
#ifndef FC_FIXED_KERNEL
    s.radius = z > 0.0 ? kernel_radius(z) : 0;
    s.inv_two_sigma2 = inv_two_sigma2_of(s.radius);
#endif
    s.clamped = unfiltered + CLAMP_RADII * particle_radius;
    s.forward = depth_range(z - depth_jump, z + depth_jump);
    s.backward = s.forward;
    s.sum = z;
    s.weight_sum = 1.0;
    return s;
}

// Tap i of a pixel's kernel, of weight w: z_fwd, z_bwd are the depths i pixels ahead and behind.
void add_tap(inout pixel_state s, bool in_kernel, float w, float z_fwd, float z_bwd)
{
    bool fwd_behind = is_behind(z_fwd, s.forward);
    bool bwd_behind = is_behind(z_bwd, s.backward);
    bool fwd_in_front = is_in_front(z_fwd, fwd_behind, s.forward);
    bool bwd_in_front = is_in_front(z_bwd, bwd_behind, s.backward);
    if (in_kernel && !fwd_behind && !fwd_in_front)
        s.forward = extended(s.forward, z_fwd);
    if (in_kernel && !bwd_behind && !bwd_in_front)
        s.backward = extended(s.backward, z_bwd);
    if (in_kernel && !fwd_in_front && !bwd_in_front) {
        s.sum += w * ((fwd_behind ? s.clamped : z_fwd) + (bwd_behind ? s.clamped : z_bwd));
        s.weight_sum += 2.0 * w;
    }
}

void main()
{
    ivec2 size = source_size;
    int length = axis.x != 0 ? size.x : size.y;
    uint listed = blocks[gl_WorkGroupID.x];
    ivec2 block = ivec2(listed & 0xffffu, listed >> 16) * BLOCK;
    ivec2 first = block + int(gl_LocalInvocationID.x) * axis.yx;
    if (any(greaterThanEqual(first, size)))
        return;
    int start = first.x * axis.x + first.y * axis.y;

    pixel_state pixel[RUN];
    float ahead[RUN], behind[RUN];   // the depths i pixels ahead of and behind each pixel of the run
    int taps = 0;
#ifdef FC_FIXED_KERNEL
    int fixed_kernel = kernel_radius(1.0);   // the same at every depth
#endif
    for (int k = 0; k < RUN; k++) {
        bool on_grid = start + k < length;
        float z = on_grid ? texel_at(first + k * axis).r : 0.0;
        float unfiltered = on_grid ? texelFetch(unfiltered_depth, first + k * axis, 0).r : 0.0;
        pixel[k] = start_pixel(z, unfiltered);
        ahead[k] = behind[k] = on_grid ? z : OFF_GRID;
#ifdef FC_FIXED_KERNEL
        taps = max(taps, z > 0.0 ? fixed_kernel : 0);
#else
        taps = max(taps, pixel[k].radius);
#endif
    }
#ifdef FC_FIXED_KERNEL
    float inv_two_sigma2 = inv_two_sigma2_of(taps);
#endif
    for (int i = 1; i <= taps; i++) {
        for (int k = 0; k < RUN - 1; k++)
            ahead[k] = ahead[k + 1];
        ahead[RUN - 1] = depth_along(first, start, start + RUN - 1 + i, length);
        for (int k = RUN - 1; k > 0; k--)
            behind[k] = behind[k - 1];
        behind[0] = depth_along(first, start, start - i, length);
#ifdef FC_FIXED_KERNEL
        float w = exp(-float(i * i) * inv_two_sigma2);
        for (int k = 0; k < RUN; k++)
            add_tap(pixel[k], pixel[k].z > 0.0, w, ahead[k], behind[k]);
#else
        for (int k = 0; k < RUN; k++)
            add_tap(pixel[k], i <= pixel[k].radius, exp(-float(i * i) * pixel[k].inv_two_sigma2), ahead[k],
                    behind[k]);
#endif
    }
    for (int k = 0; k < RUN; k++)
        if (start + k < length && pixel[k].z > 0.0)
            imageStore(filtered, first + k * axis, vec4(pixel[k].sum / pixel[k].weight_sum));
}
