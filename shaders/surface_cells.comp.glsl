#version 450 core
// Surface mesh, passes 3 and 5: marching tetrahedra (surface_tets.h). Each
// cell of a block, split into six tetrahedra along its main diagonal, gives
// each tetrahedron's triangles from its table. Counting (emit false) writes
// the cell's triangle count for the prefix sum; emitting writes its triangles
// at their scanned place, each corner the vertex of the lattice edge it lies
// on, found in the block that owns the edge (this one, or a neighbour above
// for edges that start on the block's upper faces).
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 3) uniform float iso;
layout(location = 5) uniform bool emit;
layout(location = 10) uniform uint tet_corners[6];   // four 3-bit corner codes each
layout(location = 20) uniform uint tet_cases[96];    // 16 per tetrahedron: count, then edges 3 bits each

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 6) readonly buffer Field { float field[]; };
layout(std430, binding = 10) readonly buffer EdgeScan { uint edge_scan[]; };
layout(std430, binding = 11) buffer CellScan { uint cell_scan[]; };
layout(std430, binding = 16) writeonly buffer Indices { uint indices[]; };

uint this_block();
uvec3 block_coordinates(uint key);
uint block_key(uvec3 coordinates);
uint direction_of_mask(uint m);
uint sample_index(uvec3 local);
uvec3 unpack_point(uint point);
uint pack_point(uvec3 local);
uint find_block(uint key);

// The tetrahedron edges' vertex pairs (surface_tets.c's FC_SURFACE_TET_EDGES).
const uvec2 TET_EDGES[6] = uvec2[6](uvec2(0, 1), uvec2(0, 2), uvec2(0, 3), uvec2(1, 2), uvec2(1, 3), uvec2(2, 3));

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
        uint next = emit ? cell_scan[slot] : 0u;
        for (uint t = 0u; t < 6u; t++) {
            uint corners = tet_corners[t], mask = 0u;
            for (uint v = 0u; v < 4u; v++)
                mask |= ((inside >> ((corners >> (3u * v)) & 7u)) & 1u) << v;
            uint entry = tet_cases[16u * t + mask];
            uint triangles = entry & 3u;
            if (!emit) {
                next += triangles;
                continue;
            }
            for (uint i = 0u; i < triangles; i++)
                for (uint j = 0u; j < 3u; j++) {
                    uvec2 pair = TET_EDGES[(entry >> (2u + 9u * i + 3u * j)) & 7u];
                    uint from = (corners >> (3u * pair.x)) & 7u, to = (corners >> (3u * pair.y)) & 7u;
                    indices[3u * (next + i) + j] =
                        edge_vertex(block, block_xyz, cell + corner_offset(from), direction_of_mask(from ^ to));
                }
            next += triangles;
        }
        if (!emit)
            cell_scan[slot] = next;
    }
}
