#version 450 core
// The sparse grid of a surface mesh (surface_grid.h): a compute library
// without main, linked into each surface pass: blocks of BLOCK^3 cells with
// (BLOCK + 1)^3 samples each, the upper faces included, keyed
// x | y << KEY_BITS | z << 2 KEY_BITS and listed in ascending key order; and the
// three directions of the lattice edges marching cubes put vertices on
// (surface_cubes.h). BLOCK, KEY_BITS and the other sizes come as #defines from
// surface_passes.c (FC_SURFACE_GRID marks the files that read them).

layout(location = 0) uniform uint block_count;

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };

// x, y, z: the lattice edge directions (EDGE_DIRECTIONS), and a cell edge's axis.
uvec3 direction(uint d)
{
    return uvec3(equal(uvec3(d), uvec3(0u, 1u, 2u)));
}

uvec3 block_coordinates(uint key)
{
    uint mask = (1u << KEY_BITS) - 1u;
    return uvec3(key & mask, (key >> KEY_BITS) & mask, key >> (2u * KEY_BITS));
}

uint block_key(uvec3 coordinates)
{
    return coordinates.x | coordinates.y << KEY_BITS | coordinates.z << (2u * KEY_BITS);
}

// The block this workgroup works on; block_count or more past the last one.
uint this_block()
{
    return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
}

uint sample_index(uvec3 local)
{
    return local.x + (BLOCK + 1u) * (local.y + (BLOCK + 1u) * local.z);
}

uvec3 unpack_point(uint point)
{
    return uvec3(point % BLOCK, (point / BLOCK) % BLOCK, point / (BLOCK * BLOCK));
}

uint pack_point(uvec3 local)
{
    return local.x + BLOCK * (local.y + BLOCK * local.z);
}

// The index of the block with `key`, MISSING when it is not in the grid.
uint find_block(uint key)
{
    uint lo = 0u, hi = block_count;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (block_keys[mid] < key)
            lo = mid + 1u;
        else
            hi = mid;
    }
    return lo < block_count && block_keys[lo] == key ? lo : MISSING;
}
