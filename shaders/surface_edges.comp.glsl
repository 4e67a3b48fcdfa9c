#version 450 core
// Surface mesh, passes 2 and 4: the lattice edges the isosurface crosses.
// Each block owns the edges that start at its points [0, BLOCK)^3 (three per
// point), so every edge of the grid has exactly one owner and one vertex,
// numbered by the owner's block and the edge's place in it: the mesh is
// welded by construction. Counting (emit false) writes 1 per crossed edge for
// the prefix sum; emitting writes, at each crossed edge's scanned place, the
// edge (block * BLOCK_EDGES + its place), which the vertices pass
// (surface_vertices.comp.glsl) turns into the vertex, one invocation per
// vertex: the particles summed there, not by every lane of an edge group.
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 3) uniform float iso;
layout(location = 5) uniform bool emit;

layout(std430, binding = 6) readonly buffer Field { float field[]; };
layout(std430, binding = 7) writeonly buffer VertexEdges { uint vertex_edges[]; };
layout(std430, binding = 10) buffer EdgeScan { uint edge_scan[]; };

uint this_block();
uvec3 direction(uint d);
uint sample_index(uvec3 local);
uvec3 unpack_point(uint point);

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    for (uint e = gl_LocalInvocationID.x; e < BLOCK_EDGES; e += gl_WorkGroupSize.x) {
        uint d = e % EDGE_DIRECTIONS;
        uvec3 point = unpack_point(e / EDGE_DIRECTIONS);
        uint s0 = block * BLOCK_SAMPLES + sample_index(point);
        uint s1 = block * BLOCK_SAMPLES + sample_index(point + direction(d));
        float a = field[s0], b = field[s1];
        bool crossed = (a >= iso) != (b >= iso);
        uint slot = block * BLOCK_EDGES + e;
        if (!emit)
            edge_scan[slot] = crossed ? 1u : 0u;
        else if (crossed)
            vertex_edges[edge_scan[slot]] = slot;
    }
}
