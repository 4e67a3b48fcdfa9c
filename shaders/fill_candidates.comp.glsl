#version 450 core
// The pinhole fill's second step (compute_splat.c): the tiles where
// filled_depth (pinhole_fill.glsl) may fill a pixel. It fills only where
// its walks find fluid on both sides along x and along y within the reach
// fc_pinhole_fill_apply returns (in texels); from any pixel of tile t those texels lie in the tiles t .. t +-
// reach_tiles (reach_tiles = ceil(reach / 4)) along the axis, so a
// tile without an occupied tile on each of its four sides within that reach
// (its own counting for all four) holds no pixel to fill. The others that
// hold an empty pixel are listed for pinhole_fill.comp.glsl's indirect
// dispatch: the walks run there only, where background pixels would
// otherwise all take them (and, masked, every pixel the fluid covers).

layout(binding = 6, r8ui) uniform readonly uimage2D occupied_tiles;   // fill_occupancy.comp.glsl
layout(std430, binding = 0) buffer FillTiles {
    uint groups_x;   // glDispatchComputeIndirect's workgroup counts: x = tiles listed (zeroed before), y = z = 1
    uint groups_y;
    uint groups_z;
    uint listed[];   // tile column | tile row << 16
};
layout(location = 40) uniform ivec2 source_size;
layout(location = 41) uniform int reach_tiles;

layout(local_size_x = 8, local_size_y = 8) in;

const int TILE_PX = 4;   // compute_splat.c's CULL_TILE_PX
const uint OCCUPIED = 1u, HOLLOW = 2u;   // as in fill_occupancy.comp.glsl

// Whether an occupied tile lies at t + k d, 0 <= k <= reach_tiles, inside the image's tiles.
bool occupied_along(ivec2 t, ivec2 d, ivec2 tiles)
{
    for (int k = 0; k <= reach_tiles; k++) {
        ivec2 q = t + k * d;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, tiles)))
            return false;
        if ((imageLoad(occupied_tiles, q).r & OCCUPIED) != 0u)
            return true;
    }
    return false;
}

void main()
{
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    ivec2 tiles = (source_size + TILE_PX - 1) / TILE_PX;
    if (any(greaterThanEqual(tile, tiles)))
        return;
    bool candidate = (imageLoad(occupied_tiles, tile).r & HOLLOW) != 0u &&
                     occupied_along(tile, ivec2(1, 0), tiles) && occupied_along(tile, ivec2(-1, 0), tiles) &&
                     occupied_along(tile, ivec2(0, 1), tiles) && occupied_along(tile, ivec2(0, -1), tiles);
    if (candidate)
        listed[atomicAdd(groups_x, 1u)] = uint(tile.x) | uint(tile.y) << 16;
}
