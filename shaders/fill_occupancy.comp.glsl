#version 450 core
// The pinhole fill's first step (compute_splat.c): per tile, whether any
// of its pixels holds a splatted depth (OCCUPIED) and whether any is empty
// (HOLLOW). fill_candidates.comp.glsl spreads the first to the tiles where
// a fill is possible at all and lists those of them with a pixel to fill.

uvec2 tile_depth_bits(ivec2 tile);   // tile_depths.glsl

layout(binding = 6, r8ui) uniform writeonly uimage2D occupied_tiles;
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger

layout(local_size_x = 8, local_size_y = 8) in;

const int TILE_PX = 4;   // compute_splat.c's CULL_TILE_PX
const uint OCCUPIED = 1u, HOLLOW = 2u;   // as in fill_candidates.comp.glsl

void main()
{
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile * TILE_PX, source_size)))
        return;
    uvec2 bits = tile_depth_bits(tile);
    imageStore(occupied_tiles, tile, uvec4((bits.x != 0x7f800000u ? OCCUPIED : 0u) |
                                           (bits.y == 0x7f800000u ? HOLLOW : 0u)));
}
