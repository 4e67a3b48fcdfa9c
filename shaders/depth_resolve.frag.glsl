#version 450 core
// The splatted depth (surface_splat.frag.glsl) in the pipeline's convention:
// +inf, where no sphere was drawn, becomes 0 = no fluid, except in the
// pinholes of a surface, which pinhole_fill.glsl closes.

layout(binding = 0) uniform sampler2D splat_depth;
layout(location = 52) uniform ivec2 source_size;   // the image in use: the texture may be larger

float filled_depth(ivec2 p);

float splat_depth_at(ivec2 p)
{
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, source_size)))
        return uintBitsToFloat(0x7f800000u);
    return texelFetch(splat_depth, p, 0).r;
}

layout(location = 0) out float depth;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = splat_depth_at(p);
    if (isinf(z))
        z = filled_depth(p);
    depth = isinf(z) ? 0.0 : z;
}
