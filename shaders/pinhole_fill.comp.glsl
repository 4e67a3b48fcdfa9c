#version 450 core
// The pinhole fill of the compute splat's depth (compute_splat.c), after
// depth_resolve.frag.glsl wrote every pixel without it: filled_depth
// (pinhole_fill.glsl) for the empty pixels of the tiles
// fill_candidates.comp.glsl listed, one workgroup per tile, through an
// indirect dispatch. Most of an image is background and most of the fluid
// covers its pixels, so the list is short, and the walks run nowhere else.

layout(local_size_x = 4, local_size_y = 4) in;   // compute_splat.c's CULL_TILE_PX

float filled_depth(ivec2 p);

layout(binding = 0, r32ui) uniform readonly uimage2D nearest_depth;   // float bits; +inf where no sphere is
layout(binding = 2, r32f) uniform writeonly image2D depth_out;
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger

layout(std430, binding = 0) readonly buffer FillTiles {
    uint groups_x;   // glDispatchComputeIndirect's workgroup counts: x = tiles listed, y = z = 1
    uint groups_y;
    uint groups_z;
    uint listed[];   // tile column | tile row << 16
};

float splat_depth_at(ivec2 p)
{
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, source_size)))
        return uintBitsToFloat(0x7f800000u);
    return uintBitsToFloat(imageLoad(nearest_depth, p).r);
}

void main()
{
    uint tile = listed[gl_WorkGroupID.x];
    ivec2 p = ivec2(tile & 0xffffu, tile >> 16) * ivec2(gl_WorkGroupSize.xy) + ivec2(gl_LocalInvocationID.xy);
    if (any(greaterThanEqual(p, source_size)) || !isinf(splat_depth_at(p)))
        return;
    float z = filled_depth(p);
    if (!isinf(z))
        imageStore(depth_out, p, vec4(z));
}
