#version 450 core
// The uniform grid of the anisotropy passes (anisotropy.c): cells one support
// radius wide (or wider, where the cell count is capped) over the particles'
// bounds, numbered x fastest so the three cells of a row are one range of the
// counting sort. A compute library without main, linked into each pass.

layout(location = 0) uniform uint particle_count;
layout(location = 1) uniform vec3 grid_origin;     // the particles' lower bounds
layout(location = 2) uniform float inverse_cell;   // 1 / cell width
layout(location = 3) uniform ivec3 grid_cells;

// The local_size_x of the per-particle passes (gl_WorkGroupSize is unknown
// to a compilation unit without the layout).
const uint PARTICLE_GROUP = 64u;

// The particle of this invocation: the dispatch is rows of workgroups
// (anisotropy.c), as 16M particles need more groups than one row allows.
uint particle_invocation()
{
    return gl_GlobalInvocationID.y * gl_NumWorkGroups.x * PARTICLE_GROUP + gl_GlobalInvocationID.x;
}

ivec3 cell_of(vec3 x)
{
    return clamp(ivec3(floor((x - grid_origin) * inverse_cell)), ivec3(0), grid_cells - 1);
}

uint cell_index(ivec3 c)
{
    return uint(c.x) + uint(grid_cells.x) * (uint(c.y) + uint(grid_cells.y) * uint(c.z));
}
