#version 450 core
// Counting sort, step 2: exclusive prefix sum of the cell counts, in place,
// in blocks of 1024 (256 lanes of 4). anisotropy.c runs it level by level:
// scanning a level's blocks writes each block's total to the level above;
// once that level is scanned, the add mode offsets every block of the level
// below by its scanned total.

layout(location = 0) uniform uint count;          // entries of this level
layout(location = 8) uniform uint level_offset;   // where they start in `data`
layout(location = 9) uniform uint sums_offset;    // where the level above starts
layout(location = 10) uniform bool add_sums;      // false: scan the blocks; true: add the level above

layout(std430, binding = 1) buffer Scan { uint data[]; };

layout(local_size_x = 256) in;

const uint LANES = 256u;
const uint PER_LANE = 4u;

shared uint lane_sums[LANES];

void add_block_offset(uint first)
{
    uint offset = data[sums_offset + gl_WorkGroupID.x];
    for (uint k = 0u; k < PER_LANE; k++)
        if (first + k < count)
            data[level_offset + first + k] += offset;
}

void main()
{
    uint lane = gl_LocalInvocationID.x;
    uint first = gl_WorkGroupID.x * LANES * PER_LANE + lane * PER_LANE;
    if (add_sums) {
        add_block_offset(first);
        return;
    }
    uint values[PER_LANE];
    uint sum = 0u;
    for (uint k = 0u; k < PER_LANE; k++) {
        values[k] = first + k < count ? data[level_offset + first + k] : 0u;
        sum += values[k];
    }
    // Inclusive scan of the lanes' sums (Hillis-Steele: 8 steps of 256).
    lane_sums[lane] = sum;
    barrier();
    for (uint step = 1u; step < LANES; step <<= 1) {
        uint before = lane >= step ? lane_sums[lane - step] : 0u;
        barrier();
        lane_sums[lane] += before;
        barrier();
    }
    uint running = lane_sums[lane] - sum;
    for (uint k = 0u; k < PER_LANE; k++) {
        if (first + k < count)
            data[level_offset + first + k] = running;
        running += values[k];
    }
    if (lane == LANES - 1u)
        data[sums_offset + gl_WorkGroupID.x] = lane_sums[lane];
}
