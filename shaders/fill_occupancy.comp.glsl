#version 450 core
// The pinhole fill's first step (compute_splat.c): per tile, whether any
// of its pixels holds a splatted depth (OCCUPIED) and whether any is empty
// (HOLLOW). fill_candidates.comp.glsl spreads the first to the tiles where
// a fill is possible at all and lists those of them with a pixel to fill.

layout(binding = 0, r32ui) uniform readonly uimage2D nearest_depth;   // float bits; +inf where no sphere is
layout(binding = 6, r8ui) uniform writeonly uimage2D occupied_tiles;
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger

layout(local_size_x = 8, local_size_y = 8) in;

const int TILE_PX = 4;   // compute_splat.c's CULL_TILE_PX
const uint OCCUPIED = 1u, HOLLOW = 2u;   // as in fill_candidates.comp.glsl

void main()
{
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    ivec2 first = tile * TILE_PX;
    if (any(greaterThanEqual(first, source_size)))
        return;
    // Pixels past the image's edge are never splatted nor read by the fill.
    ivec2 last = min(first + TILE_PX, source_size) - 1;
    // +inf where no sphere is; depths are positive, so their bits order as the floats.
    uint nearest = 0x7f800000u, farthest = 0u;
    for (int y = first.y; y <= last.y; y++)
        for (int x = first.x; x <= last.x; x++) {
            uint bits = imageLoad(nearest_depth, ivec2(x, y)).r;
            nearest = min(nearest, bits);
            farthest = max(farthest, bits);
        }
    imageStore(occupied_tiles, tile,
               uvec4((nearest != 0x7f800000u ? OCCUPIED : 0u) | (farthest == 0x7f800000u ? HOLLOW : 0u)));
}
