#version 450 core
// The compute splat's culling (surface_splat.comp.glsl, CULL_REST): the
// farthest depth splatted at any pixel of each tile (cull_tiles.glsl), +inf
// where a pixel holds none. A particle whose nearest possible depth lies
// behind this at every tile its box touches can win no pixel there.

layout(binding = 0, r32ui) uniform readonly uimage2D nearest_depth;   // float bits; +inf where no sphere is
layout(binding = 5, r32ui) uniform writeonly uimage2D far_tiles;
layout(location = 40) uniform ivec2 source_size;   // the image in use: the images may be larger

layout(local_size_x = 8, local_size_y = 8) in;

const int TILE_PX = 4;   // cull_tiles.glsl's

void main()
{
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    ivec2 first = tile * TILE_PX;
    if (any(greaterThanEqual(first, source_size)))
        return;
    // Pixels past the image's edge are never splatted nor read: they do not count.
    ivec2 last = min(first + TILE_PX, source_size) - 1;
    uint farthest = 0u;
    for (int y = first.y; y <= last.y; y++)
        for (int x = first.x; x <= last.x; x++)
            farthest = max(farthest, imageLoad(nearest_depth, ivec2(x, y)).r);
    imageStore(far_tiles, tile, uvec4(farthest));
}
