#version 450 core
// Counting sort, step 3: each particle goes to its cell's start plus its
// rank, with its draw slot in w, so the neighbour search reads the
// particles of a cell as one contiguous range.

uint particle_invocation();

layout(location = 0) uniform uint particle_count;

layout(std430, binding = 0) readonly buffer Positions { float positions[]; };
layout(std430, binding = 1) readonly buffer CellStarts { uint cell_starts[]; };
layout(std430, binding = 2) readonly buffer CellRanks { uvec2 cell_ranks[]; };
layout(std430, binding = 3) writeonly buffer Sorted { vec4 sorted[]; };   // xyz, slot as bits

layout(local_size_x = 64) in;

void main()
{
    uint i = particle_invocation();
    if (i >= particle_count)
        return;
    uvec2 cell_rank = cell_ranks[i];
    vec3 x = vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    sorted[cell_starts[cell_rank.x] + cell_rank.y] = vec4(x, uintBitsToFloat(i));
}
