#version 450 core
// Surface mesh, pass 5: the vertices, one invocation each (surface_edges
// wrote each vertex's lattice edge at its number): the position where the
// field, linear along the edge, meets the iso value; there the outward normal
// (minus the field's gradient) and the attributes (zeros for a frame without
// them), summed from the particles (surface_kernel.comp.glsl).
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).

layout(local_size_x = 64) in;

layout(location = 1) uniform vec3 origin;
layout(location = 2) uniform float cell;
layout(location = 3) uniform float iso;
layout(location = 8) uniform bool with_attributes;   // the frame has velocity, density or ids
layout(location = 9) uniform uint vertex_count;

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 6) readonly buffer Field { float field[]; };
layout(std430, binding = 7) readonly buffer VertexEdges { uint vertex_edges[]; };
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
vec3 field_gradient(vec3 x);
uint nearest_particle(vec3 x);

layout(std430, binding = 0) readonly buffer Particles { vec4 particles[]; };

void main()
{
    uint v = this_block() * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    if (v >= vertex_count)
        return;
    uint edge = vertex_edges[v], block = edge / BLOCK_EDGES, e = edge % BLOCK_EDGES;
    uint d = e % EDGE_DIRECTIONS;
    uvec3 point = unpack_point(e / EDGE_DIRECTIONS);
    float a = field[block * BLOCK_SAMPLES + sample_index(point)];
    float b = field[block * BLOCK_SAMPLES + sample_index(point + direction(d))];
    float t = (iso - a) / (b - a);
    uvec3 base = block_coordinates(block_keys[block]) * BLOCK;
    vec3 x = origin + (vec3(base + point) + t * vec3(direction(d))) * cell;
    vec3 g;
    vec4 mean = vec4(0.0);
    float speed = 0.0;
    uint nearest_id = 0u;
    if (with_attributes)
        field_at_vertex(x, g, mean, speed, nearest_id);
    else
        g = field_gradient(x);
    uint p = length(g) > 0.0 ? MISSING : nearest_particle(x);
    if (p != MISSING)
        g = particles[p].xyz - x;   // no field reaches x: away from the nearest particle
    float len = length(g);
    vec3 n = len > 0.0 ? -g / len : vec3(0.0, 0.0, 1.0);
    for (uint c = 0u; c < 3u; c++) {
        positions[3u * v + c] = x[c];
        normals[3u * v + c] = n[c];
    }
    vertex_attributes[v] = mean;
    vertex_extras[v] = uvec2(floatBitsToUint(speed), nearest_id);
}
