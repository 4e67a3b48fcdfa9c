#version 450 core
// The compute splat's images (surface_splat.comp.glsl) in the pipeline's
// convention: depth as float, +inf (no sphere) as 0 except in the pinholes
// of a surface, which pinhole_fill.glsl closes; thickness from fixed point
// back to world units.

layout(location = 0) uniform float chord_per_unit;   // world units per thickness step; 0 = no thickness

layout(binding = 0, r32ui) uniform readonly uimage2D nearest_depth;
layout(binding = 1, r32ui) uniform readonly uimage2D thickness_sum;
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger
layout(binding = 2, r32f) uniform writeonly image2D depth_out;
layout(binding = 3, r32f) uniform writeonly image2D thickness_out;

layout(local_size_x = 8, local_size_y = 8) in;

float filled_depth(ivec2 p);

float splat_depth_at(ivec2 p)
{
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, source_size)))
        return uintBitsToFloat(0x7f800000u);
    return uintBitsToFloat(imageLoad(nearest_depth, p).r);
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, source_size)))
        return;
#ifndef FC_THICKNESS_ONLY   // defined with the splat's (compute_splat.c): no depth was splatted
    float z = splat_depth_at(p);
    if (isinf(z))
        z = filled_depth(p);
    imageStore(depth_out, p, vec4(isinf(z) ? 0.0 : z));
#endif
#ifndef FC_DEPTH_ONLY   // no thickness was splatted
    if (chord_per_unit > 0.0)
        imageStore(thickness_out, p, vec4(float(imageLoad(thickness_sum, p).r) * chord_per_unit));
#endif
}
