#version 450 core
// Surface mesh, pass 1: the field's value at every sample of every block
// (surface_kernel.comp.glsl sums it; only the value, 4 bytes a sample: the
// gradient and the attributes are taken at the vertices, surface_edges).
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 1) uniform vec3 origin;
layout(location = 2) uniform float cell;

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 6) writeonly buffer Field { float field[]; };

uint this_block();
uvec3 block_coordinates(uint key);
float field_value(vec3 x);

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    uvec3 base = block_coordinates(block_keys[block]) * BLOCK;
    for (uint s = gl_LocalInvocationID.x; s < BLOCK_SAMPLES; s += gl_WorkGroupSize.x) {
        uvec3 local = uvec3(s % (BLOCK + 1u), (s / (BLOCK + 1u)) % (BLOCK + 1u), s / ((BLOCK + 1u) * (BLOCK + 1u)));
        field[block * BLOCK_SAMPLES + s] = field_value(origin + vec3(base + local) * cell);
    }
}
