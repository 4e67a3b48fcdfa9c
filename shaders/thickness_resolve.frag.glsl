#version 450 core
// The compute splat's thickness (surface_splat.comp.glsl: fixed point in an
// R32UI image) in world units, as the fragment splat leaves it. A
// full-screen draw for the reason depth_resolve.frag.glsl gives.

layout(binding = 0) uniform usampler2D thickness_sum;
layout(location = 0) uniform float chord_per_unit;   // world units per thickness step

layout(location = 0) out float thickness;

void main()
{
    thickness = float(texelFetch(thickness_sum, ivec2(gl_FragCoord.xy), 0).r) * chord_per_unit;
}
