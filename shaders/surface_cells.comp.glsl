#version 450 core
// Surface mesh, passes 3 and 5: marching cubes (surface_cubes.h: one rule for
// ambiguous faces, so the surface is closed and 2-manifold). Each cell of a
// block gives the triangles of its case, the mask of its corners inside.
// Counting (emit false) writes the cell's triangle count for the prefix sum;
// emitting writes its triangles at their scanned place, each corner the vertex
// of the lattice edge it lies on, found in the block that owns the edge (this
// one, or a neighbour above for edges that start on the block's upper faces).
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c),
// CUBE_CASES too.

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 3) uniform float iso;
layout(location = 5) uniform bool emit;

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 6) readonly buffer Field { float field[]; };
// 256 cases (first triangle | count << 16), then the triangles (three cell edges, 4 bits each).
layout(std430, binding = 8) readonly buffer Cubes { uint cubes[]; };
layout(std430, binding = 10) readonly buffer EdgeScan { uint edge_scan[]; };
layout(std430, binding = 11) buffer CellScan { uint cell_scan[]; };
layout(std430, binding = 16) writeonly buffer Indices { uint indices[]; };

uint this_block();
uvec3 block_coordinates(uint key);
uint block_key(uvec3 coordinates);
uint sample_index(uvec3 local);
uvec3 unpack_point(uint point);
uint pack_point(uvec3 local);
uint find_block(uint key);

// The corner where cell edge k starts (fc_surface_cube_edge_corner): edge 4 a + j starts at the j-th
// corner whose bit a is 0.
const uint EDGE_CORNERS[12] = uint[12](0u, 2u, 4u, 6u, 0u, 1u, 4u, 5u, 0u, 1u, 2u, 3u);

uvec3 corner_offset(uint code)
{
    return uvec3(code & 1u, (code >> 1) & 1u, (code >> 2) & 1u);
}

// The vertex on the lattice edge from `point` (a point of this block's cells'
// corners, [0, BLOCK]^3) in direction d.
uint edge_vertex(uint block, uvec3 block_xyz, uvec3 point, uint d)
{
    uvec3 over = uvec3(greaterThanEqual(point, uvec3(BLOCK)));
    uint owner = block;
    if (any(greaterThan(over, uvec3(0u))))
        owner = find_block(block_key(block_xyz + over));
    if (owner == MISSING)
        return MISSING;
    uint e = pack_point(point - over * BLOCK) * EDGE_DIRECTIONS + d;
    return edge_scan[owner * BLOCK_EDGES + e];
}

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    uvec3 block_xyz = block_coordinates(block_keys[block]);
    for (uint c = gl_LocalInvocationID.x; c < BLOCK_CELLS; c += gl_WorkGroupSize.x) {
        uvec3 cell = unpack_point(c);
        uint inside = 0u;
        for (uint k = 0u; k < 8u; k++)
            if (field[block * BLOCK_SAMPLES + sample_index(cell + corner_offset(k))] >= iso)
                inside |= 1u << k;
        uint slot = block * BLOCK_CELLS + c;
        uint entry = cubes[inside], first = CUBE_CASES + (entry & 0xFFFFu), triangles = entry >> 16;
        if (!emit) {
            cell_scan[slot] = triangles;
            continue;
        }
        uint next = cell_scan[slot];
        for (uint i = 0u; i < triangles; i++) {
            uint edges = cubes[first + i];
            for (uint j = 0u; j < 3u; j++) {
                uint k = (edges >> (4u * j)) & 15u;
                indices[3u * (next + i) + j] = edge_vertex(block, block_xyz, cell + corner_offset(EDGE_CORNERS[k]), k / 4u);
            }
        }
    }
}
