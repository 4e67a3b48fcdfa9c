#version 450 core
// Surface mesh, pass 1: the field's value at every sample of every block
// (surface_kernel.comp.glsl sums it; only the value, 4 bytes a sample: the
// gradient and the attributes are taken at the vertices, surface_edges).
// The grid's sizes come as #defines (FC_SURFACE_GRID, surface_passes.c).
//
// A solid block, one every sample of which is proven at or above the iso value
// by the particles nearest it (field_reaches), gets iso at every sample instead
// of its sums: the surface cannot cross it, so the crossed pass drops it and
// nothing reads its field again. Inside a body of fluid most blocks are solid,
// and their full sums were most of the extraction's time; every other block's
// field is summed as before, so the mesh is the same bit for bit. Run twice
// (`stage`): first each block proves the samples it owns (its cells' lower
// corners, 8^3 of its 9^3) and flags which parts are (in the Crossed buffer,
// which the crossed pass overwrites later); then a block is solid when it and
// the seven blocks owning its upper faces' samples have proven those, so no
// sample is proven twice.

layout(local_size_x = 64) in;

layout(location = 0) uniform uint block_count;
layout(location = 1) uniform vec3 origin;
layout(location = 2) uniform float cell;
layout(location = 3) uniform float iso;
layout(location = 10) uniform int stage;   // 0: prove the owned samples; 1: the field

layout(std430, binding = 3) readonly buffer BlockKeys { uint block_keys[]; };
layout(std430, binding = 5) buffer Owned { uint owned_proven[]; };   // per block, stage 0's proven parts
layout(std430, binding = 6) writeonly buffer Field { float field[]; };

uint this_block();
uvec3 block_coordinates(uint key);
uint block_key(uvec3 coordinates);
uint find_block(uint key);
uvec3 unpack_point(uint point);
uint sample_index(uvec3 local);
ivec3 bin_of(vec3 x);
uint particles_in(ivec3 lo, ivec3 hi);
float field_value(vec3 x);
bool field_reaches(vec3 x, float threshold);

shared float threshold;   // what field_reaches must reach to prove a sample of the block
shared uint unproven;      // bit m: part m of the owned samples (parts_of) has one not proven
shared bool is_solid;      // stage 1's verdict on the block

vec3 sample_position(uvec3 base, uvec3 local)
{
    return origin + vec3(base + local) * cell;
}

// The block's sample number t in an order that keeps rows of BLOCK along x together (an invocation's lanes
// then read the same rows of bins): the BLOCK^3 it owns, then the upper y face's rows (x < BLOCK), the upper
// z face's (x, y < BLOCK), and the upper x face.
uvec3 sample_local(uint t)
{
    const uint owned = BLOCK * BLOCK * BLOCK, face_rows = (BLOCK + 1u) + BLOCK;
    if (t < owned)
        return unpack_point(t);
    t -= owned;
    if (t < face_rows * BLOCK) {
        uint row = t / BLOCK, x = t % BLOCK;
        return row <= BLOCK ? uvec3(x, BLOCK, row) : uvec3(x, row - (BLOCK + 1u), BLOCK);
    }
    t -= face_rows * BLOCK;
    return uvec3(BLOCK, t % (BLOCK + 1u), t / (BLOCK + 1u));
}

// iso raised by a margin for rounding: field_reaches sums a subset of field_value's
// terms (each in [0, 1], computed by the same code but perhaps contracted
// differently, within 40 units in the last place) in another order, n terms at
// most, where n counts the particles of every bin any sample of the block reads
// (2 BIN_SPLIT bins past the bins of its corners). Each sum is within n 2^-24
// of its exact value relatively, so a subset sum at or above iso (1 + 64 n
// 2^-24) leaves the full sum at or above iso.
float solid_threshold(uvec3 base)
{
    ivec3 lo = bin_of(sample_position(base, uvec3(0u))) - int(BIN_SPLIT);
    ivec3 hi = bin_of(sample_position(base, uvec3(BLOCK))) + int(BIN_SPLIT);
    return iso * (1.0 + 64.0 * float(particles_in(lo, hi)) / 16777216.0);
}

// The parts of a block's owned samples the sample at `local` belongs to: bit m
// for each m of 0..7 whose axes (1 x, 2 y, 4 z) all have local 0. Part 0 is every
// owned sample; part m > 0, the samples the block shares with the block below it
// along m's axes (a face, an edge, the corner), that one's upper ones.
uint parts_of(uvec3 local)
{
    uint zero = uint(local.x == 0u) | uint(local.y == 0u) << 1u | uint(local.z == 0u) << 2u;
    uint parts = 0u;
    for (uint m = 0u; m < 8u; m++)
        if ((m & zero) == m)
            parts |= 1u << m;
    return parts;
}

// Stage 0: which parts of the samples the block owns are all proven at or
// above iso (bit m, parts_of), each sample tried until every part it belongs to
// has one that is not.
void prove_owned(uint block, uvec3 base)
{
    if (gl_LocalInvocationID.x == 0u) {
        unproven = 0u;
        threshold = solid_threshold(base);
    }
    barrier();
    for (uint c = gl_LocalInvocationID.x; c < BLOCK_CELLS && unproven != 0xFFu; c += gl_WorkGroupSize.x) {
        uvec3 local = unpack_point(c);
        uint parts = parts_of(local);
        if ((unproven & parts) != parts && !field_reaches(sample_position(base, local), threshold))
            atomicOr(unproven, parts);
    }
    barrier();
    if (gl_LocalInvocationID.x == 0u)
        owned_proven[block] = ~unproven & 0xFFu;
}

// Whether every sample of the block is proven: those it owns, and those of its
// upper faces, edges and corner, owned by the seven blocks above it (part k of
// the block k above, k's axes offset by one). A block missing from the grid is
// out of every particle's reach: its samples' field is 0.
bool solid(uint block, uvec3 coordinates)
{
    if ((owned_proven[block] & 1u) == 0u)
        return false;
    for (uint k = 1u; k < 8u; k++) {
        uint above = find_block(block_key(coordinates + uvec3(k & 1u, (k >> 1u) & 1u, k >> 2u)));
        if (above == MISSING || (owned_proven[above] >> k & 1u) == 0u)
            return false;
    }
    return true;
}

void main()
{
    uint block = this_block();
    if (block >= block_count)
        return;
    uvec3 coordinates = block_coordinates(block_keys[block]), base = coordinates * BLOCK;
    if (stage == 0) {
        prove_owned(block, base);
        return;
    }
    if (gl_LocalInvocationID.x == 0u)
        is_solid = solid(block, coordinates);
    barrier();
    for (uint t = gl_LocalInvocationID.x; t < BLOCK_SAMPLES; t += gl_WorkGroupSize.x) {
        uvec3 local = sample_local(t);
        field[block * BLOCK_SAMPLES + sample_index(local)] = is_solid ? iso : field_value(sample_position(base, local));
    }
}
