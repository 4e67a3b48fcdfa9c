#version 450 core
// Surface mesh, pass 1: the field's value at every sample of every block
// (surface_kernel.comp.glsl sums it; only the value, 4 bytes a sample: the
// gradient and the attributes are taken at the vertices, surface_edges).
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).
//
// A solid block, one every sample of which is proven at or above the iso value
// by the few particles nearest it (field_reaches), gets iso at every sample
// instead of its sums: the surface cannot cross it, so the crossed pass drops it
// and nothing reads its field again. Inside a body of fluid most blocks are solid,
// and their full sums were most of the extraction's time; every other block's
// field is summed as before, so the mesh is the same bit for bit.

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 1) uniform vec3 origin;
layout(location = 2) uniform float cell;
layout(location = 3) uniform float iso;

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 6) writeonly buffer Field { float field[]; };

uint this_block();
uvec3 block_coordinates(uint key);
ivec3 bin_of(vec3 x);
uint particles_in(ivec3 lo, ivec3 hi);
float field_value(vec3 x);
bool field_reaches(vec3 x, float threshold);

shared float threshold;   // what the nearest particles' sum must reach to prove a sample at or above iso
shared uint unproven;     // 1 once a sample of the block is not proven

vec3 sample_position(uvec3 base, uint s)
{
    uvec3 local = uvec3(s % (BLOCK + 1u), (s / (BLOCK + 1u)) % (BLOCK + 1u), s / ((BLOCK + 1u) * (BLOCK + 1u)));
    return origin + vec3(base + local) * cell;
}

// iso raised by a margin for rounding: field_reaches sums a subset of field_value's
// terms (each in [0, 1], computed by the same code but perhaps contracted
// differently, within 40 units in the last place), n terms at most, where n
// counts the particles of every bin any sample of the block reads (2 BIN_SPLIT
// bins past the bins of its corners). Each sum is within n 2^-24 of its exact
// value relatively, so a subset sum at or above iso (1 + 64 n 2^-24) leaves
// the full sum at or above iso.
float solid_threshold(uvec3 base)
{
    ivec3 lo = bin_of(sample_position(base, 0u)) - int(BIN_SPLIT);
    ivec3 hi = bin_of(sample_position(base, BLOCK_SAMPLES - 1u)) + int(BIN_SPLIT);
    return iso * (1.0 + 64.0 * float(particles_in(lo, hi)) / 16777216.0);
}

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    uvec3 base = block_coordinates(block_keys[block]) * BLOCK;
    if (gl_LocalInvocationID.x == 0u) {
        threshold = solid_threshold(base);
        unproven = 0u;
    }
    barrier();
    for (uint s = gl_LocalInvocationID.x; s < BLOCK_SAMPLES && unproven == 0u; s += gl_WorkGroupSize.x)
        if (!field_reaches(sample_position(base, s), threshold))
            atomicOr(unproven, 1u);
    barrier();
    bool solid = unproven == 0u;
    for (uint s = gl_LocalInvocationID.x; s < BLOCK_SAMPLES; s += gl_WorkGroupSize.x)
        field[block * BLOCK_SAMPLES + s] = solid ? iso : field_value(sample_position(base, s));
}
