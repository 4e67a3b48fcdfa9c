#version 450 core
// Counting sort, step 1: each particle counts itself into its cell and keeps
// its rank there (the atomic's old value), so the scatter needs no atomics.

uint particle_invocation();
ivec3 cell_of(vec3 x);
uint cell_index(ivec3 c);

layout(location = 0) uniform uint particle_count;

layout(std430, binding = 0) readonly buffer Positions { float positions[]; };   // xyz per particle
layout(std430, binding = 1) buffer CellCounts { uint cell_counts[]; };
layout(std430, binding = 2) writeonly buffer CellRanks { uvec2 cell_ranks[]; };   // cell, rank in it

layout(local_size_x = 64) in;

void main()
{
    uint i = particle_invocation();
    if (i >= particle_count)
        return;
    vec3 x = vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    uint cell = cell_index(cell_of(x));
    cell_ranks[i] = uvec2(cell, atomicAdd(cell_counts[cell], 1u));
}
