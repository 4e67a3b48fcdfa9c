#version 450 core
// Surface mesh, passes 2 and 4: the lattice edges the isosurface crosses.
// Each block owns the edges that start at its points [0, BLOCK)^3 (seven per
// point), so every edge of the grid has exactly one owner and one vertex,
// numbered by the owner's block and the edge's place in it: the mesh is
// welded by construction. Counting (emit false) writes 1 per crossed edge for
// the prefix sum; emitting writes each crossed edge's vertex at its scanned
// place: the position where the field, linear along the edge, meets the iso
// value; there the outward normal (minus the field's gradient) and the
// attributes, from the particles (surface_kernel.comp.glsl).
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 1) uniform vec3 origin;
layout(location = 2) uniform float cell;
layout(location = 3) uniform float iso;
layout(location = 5) uniform bool emit;

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 6) readonly buffer Field { float field[]; };
layout(std430, binding = 10) buffer EdgeScan { uint edge_scan[]; };
layout(std430, binding = 12) writeonly buffer Positions { float positions[]; };
layout(std430, binding = 13) writeonly buffer Normals { float normals[]; };
layout(std430, binding = 14) writeonly buffer VertexAttributes { vec4 vertex_attributes[]; };
layout(std430, binding = 15) writeonly buffer VertexExtras { uvec2 vertex_extras[]; };

uint this_block();
uvec3 block_coordinates(uint key);
uvec3 direction(uint d);
uint sample_index(uvec3 local);
uvec3 unpack_point(uint point);

void field_at_vertex(vec3 x, out vec3 gradient, out vec4 mean, out float speed, out uint nearest_id);

void write_vertex(uint v, uvec3 base, uvec3 point, uint d, float a, float b)
{
    float t = (iso - a) / (b - a);
    vec3 x = origin + (vec3(base + point) + t * vec3(direction(d))) * cell;
    vec3 g;
    vec4 mean;
    float speed;
    uint nearest_id;
    field_at_vertex(x, g, mean, speed, nearest_id);
    float len = length(g);
    vec3 n = len > 0.0 ? -g / len : vec3(0.0, 0.0, 1.0);
    for (uint c = 0u; c < 3u; c++) {
        positions[3u * v + c] = x[c];
        normals[3u * v + c] = n[c];
    }
    vertex_attributes[v] = mean;
    vertex_extras[v] = uvec2(floatBitsToUint(speed), nearest_id);
}

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    uvec3 base = block_coordinates(block_keys[block]) * BLOCK;
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
            write_vertex(edge_scan[slot], base, point, d, a, b);
    }
}
