#version 450 core
// Surface mesh, pass 2: whether the surface crosses a block, from the field at
// its samples (pass 1): some sample at or above the iso value and some below.
// Only those blocks are kept for the edges, cells and vertices (surface_mesher.c):
// the interior of a body of fluid and the air around it hold no surface, and
// their scan entries were most of the grid's memory. A crossed lattice edge on
// a face two blocks share marks both, so a cell always finds the block that
// owns each of its edges. The grid's sizes come as #defines (FC_SURFACE_GRID).

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 3) uniform float iso;

layout(std430, binding = 5) writeonly buffer Crossed { uint crossed[]; };
layout(std430, binding = 6) readonly buffer Field { float field[]; };

uint this_block();

shared uint seen;   // bit 0: a sample at or above iso; bit 1: one below

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    if (gl_LocalInvocationID.x == 0u)
        seen = 0u;
    barrier();
    uint mine = 0u;
    for (uint s = gl_LocalInvocationID.x; s < BLOCK_SAMPLES; s += gl_WorkGroupSize.x)
        mine |= field[block * BLOCK_SAMPLES + s] >= iso ? 1u : 2u;
    atomicOr(seen, mine);
    barrier();
    if (gl_LocalInvocationID.x == 0u)
        crossed[block] = seen == 3u ? 1u : 0u;
}
