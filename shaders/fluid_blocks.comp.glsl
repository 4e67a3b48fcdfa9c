#version 450 core
// Lists the 8x8-pixel blocks of a depth image that hold fluid (depth > 0), as
// the workgroups of an indirect dispatch (server/render/fluid_blocks.c): a
// filter that leaves the background alone then runs on these blocks only.
// On llvmpipe a dispatch over the whole image pays for every block, fluid or
// not (a branch skips nothing), and the benchmark's fluid lies in a quarter
// of the blocks.
// One invocation per block reads its 64 texels as 16 gathers of 2x2 (on
// llvmpipe a gather costs about what one fetch does); a block with fluid
// takes the next slot of the list, one atomic per such block.

layout(local_size_x = 8, local_size_y = 8) in;

#define BLOCK 8

layout(binding = 0) uniform sampler2D depth;
layout(location = 40) uniform ivec2 source_size;   // the image in use; the texture may be larger (stale texels)

layout(std430, binding = 0) buffer FluidBlocks {
    uint groups_x;   // glDispatchComputeIndirect's workgroup counts: x = blocks listed (zeroed before), y = z = 1
    uint groups_y;
    uint groups_z;
    uint blocks[];   // block column | block row << 16
};

// Whether any of the 2x2 texels from `p` (lower left) up holds fluid within the image in use.
bool quad_has_fluid(ivec2 p, vec2 texel_size)
{
    // At the corner the four texels share, a gather returns them in the
    // order (x, y+1), (x+1, y+1), (x+1, y), (x, y).
    vec4 z = textureGather(depth, vec2(p + 1) * texel_size);
    bvec2 x_in = lessThan(p.xx + ivec2(0, 1), source_size.xx);
    bvec2 y_in = lessThan(p.yy + ivec2(0, 1), source_size.yy);
    bvec4 inside = bvec4(x_in.x && y_in.y, x_in.y && y_in.y, x_in.y && y_in.x, x_in.x && y_in.x);
    return any(greaterThan(mix(vec4(0.0), z, inside), vec4(0.0)));
}

void main()
{
    ivec2 block = ivec2(gl_GlobalInvocationID.xy);
    vec2 texel_size = 1.0 / vec2(textureSize(depth, 0));
    bool fluid = false;
    for (int y = 0; y < BLOCK; y += 2)
        for (int x = 0; x < BLOCK; x += 2)
        {
            bool quad = quad_has_fluid(block * BLOCK + ivec2(x, y), texel_size);
            fluid = fluid || quad;
        }
    if (fluid)
        blocks[atomicAdd(groups_x, 1u)] = uint(block.x) | uint(block.y) << 16;
}
