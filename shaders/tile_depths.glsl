#version 450 core
// The splatted depths of one culling tile (cull_tiles.glsl's TILE_PX pixels
// on a side) reduced to their nearest and farthest bits. A library without a
// stage, linked into splat_tiles.comp.glsl (the culling's far depth per
// tile) and fill_occupancy.comp.glsl (the tiles the pinhole fill looks at).

layout(binding = 0, r32ui) uniform readonly uimage2D nearest_depth;   // float bits; +inf where no sphere is
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger

const int TILE_PX = 4;   // cull_tiles.glsl's, compute_splat.c's CULL_TILE_PX

// (nearest, farthest) bits over the tile's pixels inside the image: pixels
// past its edge are never splatted nor read, and do not count. Depths are
// positive, so their bits order as the floats; +inf where no sphere is. The
// tile must start inside the image.
uvec2 tile_depth_bits(ivec2 tile)
{
    ivec2 first = tile * TILE_PX;
    ivec2 last = min(first + TILE_PX, source_size) - 1;
    uvec2 range = uvec2(0x7f800000u, 0u);
    for (int y = first.y; y <= last.y; y++)
        for (int x = first.x; x <= last.x; x++) {
            uint bits = imageLoad(nearest_depth, ivec2(x, y)).r;
            range = uvec2(min(range.x, bits), max(range.y, bits));
        }
    return range;
}
