#version 450 core
// The first step of the compute splat's culling (surface_splat.comp.glsl,
// FC_DEPTH_ONLY): each sampled particle's centre depth into its tile's
// minimum, the fluid's front per tile. A pass of its own, so that the splat's programs do
// not carry its atomic, which llvmpipe would run masked in every phase.

vec4 load_particle(uint i);
ivec2 centre_tile(vec3 centre, float depth);

layout(location = 6) uniform uint particle_count;
layout(location = 14) uniform uint stride;   // a sample: every stride-th particle (compute_splat.c)

layout(binding = 4, r32ui) uniform uimage2D front_tiles;   // bits of the nearest centre's depth, +inf: none

layout(local_size_x = 64) in;

void main()
{
    uint i = (gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x) * stride;
    if (i >= particle_count)
        return;
    vec3 centre = load_particle(i).xyz;
    float depth = -centre.z;
    if (depth > 0.0)
        imageAtomicMin(front_tiles, centre_tile(centre, depth), floatBitsToUint(depth));
}
