#version 450 core
// The compute splat's images (surface_splat.comp.glsl) in the pipeline's
// convention: depth as float, +inf (no sphere) as 0 except in the pinholes
// of a surface, which pinhole_fill.glsl closes; thickness from fixed point
// back to world units. Built with FC_FILL_TILES (compute_splat.c's marked
// resolve, where the walks are long enough to pay for the marking), the
// fill's walks run only in the tiles fill_candidates.comp.glsl marks:
// elsewhere (most of the background) they would find nothing, and llvmpipe
// skips them where no lane of a SIMD group needs them.

layout(location = 0) uniform float chord_per_unit;   // world units per thickness step; 0 = no thickness

layout(binding = 0, r32ui) uniform readonly uimage2D nearest_depth;
layout(binding = 1, r32ui) uniform readonly uimage2D thickness_sum;
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger
layout(binding = 2, r32f) uniform writeonly image2D depth_out;
layout(binding = 3, r32f) uniform writeonly image2D thickness_out;
#ifdef FC_FILL_TILES
layout(binding = 7, r8ui) uniform readonly uimage2D fill_tiles;   // per 4x4 tile: 0 where no pixel is filled
#endif

layout(local_size_x = 8, local_size_y = 8) in;

float filled_depth(ivec2 p);

float splat_depth_at(ivec2 p)
{
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, source_size)))
        return uintBitsToFloat(0x7f800000u);
    return uintBitsToFloat(imageLoad(nearest_depth, p).r);
}

// Whether the fill may fill the empty pixel p.
bool may_fill(ivec2 p)
{
#ifdef FC_FILL_TILES
    return imageLoad(fill_tiles, p / 4).r != 0u;   // 4: compute_splat.c's CULL_TILE_PX
#else
    return true;
#endif
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, source_size)))
        return;
#ifndef FC_THICKNESS_ONLY   // defined with the splat's (compute_splat.c): no depth was splatted
    float z = splat_depth_at(p);
    if (isinf(z) && may_fill(p))
        z = filled_depth(p);
    imageStore(depth_out, p, vec4(isinf(z) ? 0.0 : z));
#endif
#ifndef FC_DEPTH_ONLY   // no thickness was splatted
    if (chord_per_unit > 0.0)
        imageStore(thickness_out, p, vec4(float(imageLoad(thickness_sum, p).r) * chord_per_unit));
#endif
}
