#version 450 core
// The compute splat's culling (surface_splat.comp.glsl, CULL_REST): the
// farthest depth splatted at any pixel of each tile (cull_tiles.glsl), +inf
// where a pixel holds none. A particle whose nearest possible depth lies
// behind this at every tile its box touches can win no pixel there.

uvec2 tile_depth_bits(ivec2 tile);   // tile_depths.glsl

layout(binding = 5, r32ui) uniform writeonly uimage2D far_tiles;
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger

layout(local_size_x = 8, local_size_y = 8) in;

const int TILE_PX = 4;   // cull_tiles.glsl's

void main()
{
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile * TILE_PX, source_size)))
        return;
    imageStore(far_tiles, tile, uvec4(tile_depth_bits(tile).y));
}
