#version 450 core
// The splatted depth (surface_splat.frag.glsl) in the pipeline's convention:
// +inf, where no sphere was drawn, becomes 0 = no fluid.

layout(binding = 0) uniform sampler2D splat_depth;

layout(location = 0) out float depth;

void main()
{
    float z = texelFetch(splat_depth, ivec2(gl_FragCoord.xy), 0).r;
    depth = isinf(z) ? 0.0 : z;
}
