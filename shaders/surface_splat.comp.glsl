#version 450 core
// Depth and thickness of the spheres (or ellipsoids, walked over their
// bounding spheres) in one splat, like surface_splat.frag.glsl
// but without the rasterizer: one invocation per particle walks the pixels of
// its sphere's projected bounding box (sphere_bounds.glsl), row by row over
// the columns the silhouette can reach (splat_walk_rows.glsl) or, for sprites
// of at most 2x2 pixels, without a loop (splat_walk_tiny.glsl), and
// ray-casts each (sphere_ray.glsl,
// thickness_chord.glsl: the fragment splat's arithmetic, so both find the
// same pixels and depths).
// The nearest depth wins by imageAtomicMin on the float's bits, which order
// like the floats because depths are positive; thickness is summed by
// imageAtomicAdd in fixed point (llvmpipe's GL has no float image atomics).
// Atomics on storage buffers instead of images measured no faster on
// llvmpipe (bench/RESULTS.md, fifth round).
// depth_resolve.frag.glsl and thickness_resolve.frag.glsl turn both into the fragment splat's images.
// Faster on llvmpipe than point sprites up to at least 64 px, where their
// set-up is serial (bench/RESULTS.md, "The splat and the smoothing on
// llvmpipe"); depth_pass.c chooses.

// The particle's shape, sphere or ellipsoid (sphere_shape.comp.glsl,
// ellipsoid_shape.comp.glsl): its view-space centre and bounding radius, and
// the ray cast.
vec4 load_particle(uint i);
vec3 loaded_world_centre();
bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord);
float thickness_above_floor(vec2 pixel, float depth, float chord);
float volume_above_floor(vec3 centre, float radius);
vec2 projected_interval(float lateral, float depth, float focal, float radius);
bool particle_ndc_bounds(vec3 view_centre, vec2 focal, out vec4 box);

layout(location = 1) uniform vec4 projection;        // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;          // pixels
layout(location = 6) uniform uint particle_count;
layout(location = 7) uniform float units_per_chord;  // thickness steps per longest chord; 0 = no thickness
layout(location = 8) uniform float max_chord;        // the longest chord a particle can have (world units)

layout(binding = 0, r32ui) uniform uimage2D nearest_depth;   // float bits; +inf where no sphere is
layout(binding = 1, r32ui) uniform uimage2D thickness_sum;   // fixed point, units_per_chord per longest chord

layout(local_size_x = 64) in;

// As sphere.vert.glsl's quads: rounding loses no pixel centre on the bounds.
const float MARGIN_PIXELS = 0.25;

#if defined(FC_THICKNESS_FOOTPRINT) || defined(FC_FUSED_THICKNESS)
// The thickness of spheres that cover a few pixels (compute_splat.c builds
// this for the spheres' thickness-only splat with the small walks: the
// thickness at a reduced scale, the shadow map; and with FC_FUSED_THICKNESS
// into the camera's culled depth, below): a sphere far away next to its
// size projects to an ellipse over which its chord falls off as
// 2r sqrt(1 - |offset|^2), offset measured in the ellipse's half extents.
// That replaces the ray cast and the floor's clipping per pixel, which took
// half of the 1M-particle thickness splat's instructions
// (bench/RESULTS.md), by a few multiplications; the floor takes its share
// per particle, the fraction of the sphere's volume above it.
// Each sphere adds its volume exactly. Its chord sampled at the pixel
// centres it covers adds more or less than its volume by where it falls
// between them (a sphere two pixels across covers two to five centres),
// which drew the particles' lattice into the thickness as a ripple at their
// spacing (grain on a block's face) and let a sphere narrower than a pixel
// vanish between the centres. So the chord's profile only weights the
// pixels of a kernel at least KERNEL_MIN_PX in radius (one that always holds
// a pixel centre), and the weights share out the volume.
const float PI = 3.14159265358979;
// Every point of the plane has a pixel centre within 0.71 pixels; a little
// more and the nearest centre weighs at least a third. A wider minimum
// spreads a tiny sphere smoother but onto more pixels: a radius of 1 cost
// 1M particles (0.6 px at a quarter of 1024x768) 8% more (bench/RESULTS.md).
const float KERNEL_MIN_PX = 0.75;

vec2 footprint_centre;   // the silhouette's centre, in pixel indices
vec2 footprint_scale;    // 1 / the kernel's half extents (pixels)
float footprint_units;   // thickness units per unit of weight

#ifdef FC_FUSED_SUN
// The sun's thickness (FC_FUSED_SUN, below), summed as thickness_sum.
layout(binding = 3, r32ui) uniform uimage2D sun_sum;
#endif

// Pixel p's weight in the footprint; with `add` (a constant where it is
// called, as `sun`, so the compiler keeps one atomic), its share added into
// the sun's thickness or the camera's.
float footprint_pixel(ivec2 p, bool add, bool sun)
{
    vec2 offset = (vec2(p) - footprint_centre) * footprint_scale;
    float weight = sqrt(max(1.0 - dot(offset, offset), 0.0));
    if (add && weight > 0.0) {
        uint units = uint(weight * footprint_units + 0.5);
#ifdef FC_FUSED_SUN
        if (sun)
            imageAtomicAdd(sun_sum, p, units);
        else
#endif
            imageAtomicAdd(thickness_sum, p, units);
    }
    return weight;
}

// The weights' sum over the box [lo, hi], each pixel's share added with
// `add`. As splat_walk_small.glsl: the 3x3 candidates with loops the compiler
// unrolls (on llvmpipe a loop the SIMD group runs costs more than the
// candidates it skips), then loops over what a larger box holds beyond.
float visit_footprint(ivec2 lo, ivec2 hi, bool add, bool sun)
{
    float sum = 0.0;
    for (int dy = 0; dy < 3; dy++)
        for (int dx = 0; dx < 3; dx++)
            if (all(lessThanEqual(lo + ivec2(dx, dy), hi)))
                sum += footprint_pixel(lo + ivec2(dx, dy), add, sun);
    for (int x = lo.x + 3; x <= hi.x; x++)
        for (int y = lo.y; y <= min(hi.y, lo.y + 2); y++)
            sum += footprint_pixel(ivec2(x, y), add, sun);
    for (int y = lo.y + 3; y <= hi.y; y++)
        for (int x = lo.x; x <= hi.x; x++)
            sum += footprint_pixel(ivec2(x, y), add, sun);
    return sum;
}

// Up to this half extent (pixels) the chord's samples are summed to share
// out the volume; past it they add up to it within a few percent, as the ray
// casts of larger sprites do.
const float SHARED_VOLUME_MAX_PX = 4.0;

// The sphere whose projected interval is x_range, y_range (NDC) into an
// image of `size` pixels: `reach`, its radius, and `above`, the share of its
// volume above the floor, make its volume.
void splat_footprint_into(vec2 x_range, vec2 y_range, float reach, float above, vec2 size, bool sun)
{
    vec2 first = (vec2(x_range.x, y_range.x) + 1.0) * 0.5 * size - 0.5;
    vec2 last = (vec2(x_range.y, y_range.y) + 1.0) * 0.5 * size - 0.5;
    vec2 half_extent = max(0.5 * (last - first), vec2(1e-3));
    vec2 kernel = max(half_extent, vec2(KERNEL_MIN_PX));
    footprint_centre = 0.5 * (first + last);
    footprint_scale = 1.0 / kernel;
    ivec2 lo = ivec2(ceil(footprint_centre - kernel)), hi = ivec2(floor(footprint_centre + kernel));
    footprint_units = min(2.0 * reach * above / max_chord, 1.0) * units_per_chord;   // at the centre's chord
    if (max(kernel.x, kernel.y) <= SHARED_VOLUME_MAX_PX) {
        // The chord over the silhouette's ellipse integrates to 2 pi / 3
        // times its half extents times the centre's chord: the volume
        // (the sum is at least a third, KERNEL_MIN_PX).
        footprint_units *= (2.0 * PI / 3.0) * half_extent.x * half_extent.y / visit_footprint(lo, hi, false, sun);
    }
    visit_footprint(max(lo, ivec2(0)), min(hi, ivec2(size) - 1), true, sun);
}
#endif

#ifndef FC_THICKNESS_FOOTPRINT
#ifdef FC_THICKNESS_ONLY
// The thickness alone (the reduced scale, the shadow map) takes the floor's
// share per particle too, the fraction of its volume above it, instead of
// clipping each ray: the floor lies under every particle's sphere
// (environment.c), so that is 1 but for particles larger than the frame's
// radius, and the per-ray clipping was a fifth of the splat's instructions
// (bench/RESULTS.md). Set per particle by main().
float particle_above_floor;
#endif

void splat_pixel(ivec2 p, vec3 centre)
{
    vec2 pixel = vec2(p) + 0.5;
    float depth, chord;
    if (!cast_particle_ray(pixel, centre, depth, chord))
        return;
    float ndc_z = (projection.w - projection.z * depth) / depth;
    // In front of the near plane no depth is seen, but the fluid there still
    // has thickness. Atomics run lane by lane on llvmpipe, a load is one
    // gather: most spheres are behind another already, and only the nearer
    // ones need the atomic. A stale load can only read a larger depth than
    // the current one, so no nearer depth is lost.
    // FC_THICKNESS_ONLY (compute_splat.c, for the sun's view without
    // meshes): nobody reads the depth, and its load and atomic go.
    // FC_DEPTH_ONLY (the camera's depth where the thickness pass splats the
    // thickness at a reduced scale): the thickness's arithmetic and atomic go.
#ifndef FC_THICKNESS_ONLY
    uint bits = floatBitsToUint(depth);
    if (ndc_z >= -1.0 && bits < imageLoad(nearest_depth, p).r)
        imageAtomicMin(nearest_depth, p, bits);
#endif
#ifndef FC_DEPTH_ONLY
    if (units_per_chord > 0.0) {
#ifdef FC_THICKNESS_ONLY
        float share = min(chord * particle_above_floor / max_chord, 1.0);
#else
        float share = min(thickness_above_floor(pixel, depth, chord) / max_chord, 1.0);
#endif
        imageAtomicAdd(thickness_sum, p, uint(share * units_per_chord + 0.5));
    }
#endif
}
#endif

// The pixels of the box [lo, hi] whose rays may meet the particle, each
// passed to splat_pixel: splat_walk_rows.glsl (any size) or
// splat_walk_tiny.glsl (boxes of at most 2x2 pixels), compute_splat.c
// links one of them.
void walk_pixels(ivec2 lo, ivec2 hi, vec3 centre, float reach);

#ifdef FC_DEPTH_ONLY
// Culling hidden particles (compute_splat.c runs the depth in steps). The
// splat's cost is its pixels, and most particles of a dense fluid lie under
// others: splatted after the fluid's front, a particle whose nearest
// possible depth lies behind everything splatted over its whole box cannot
// win a pixel, and is not walked. The result is the same minimum, bit for
// bit; only the work changes.
//  1. splat_front.comp.glsl: a sample's centre depths (every third
//     particle's) into their tile's minimum (front_tiles; tiles:
//     cull_tiles.glsl).
//  2. CULL_NEAR: the particles near their tile's front (within two bounding
//     radii and a slack for the tile's extent) are walked: the fluid's front.
//  3. CULL_REST: the others, after far_tiles took the farthest depth of
//     each tile's pixels (splat_tiles.comp.glsl): walked unless every tile
//     their box touches lies wholly in front of them.
// On llvmpipe a loop ends once no lane needs it, so a SIMD group whose
// particles are all skipped costs no walk; an `if` would run both sides.
const int CULL_NONE = 0;
const int CULL_NEAR = 1;
const int CULL_REST = 2;

ivec2 tile_of(ivec2 pixel);
ivec2 centre_tile(vec3 centre, float depth);

layout(location = 11) uniform int cull_phase;
layout(location = 12) uniform float slack_per_depth;   // world units per unit of depth: a tile's extent, times a margin
layout(binding = 4, r32ui) uniform readonly uimage2D front_tiles;   // bits of the nearest particle centre's depth
layout(binding = 5, r32ui) uniform readonly uimage2D far_tiles;     // bits of the farthest depth of the tile's pixels

// Near the front: within two bounding radii and the slack of the nearest centre of its tile.
bool near_front(vec3 centre, float depth, float reach)
{
    float front = uintBitsToFloat(imageLoad(front_tiles, centre_tile(centre, depth)).r);
    return depth <= front + 2.0 * reach + slack_per_depth * depth;
}

// Whether every tile the box [lo, hi] touches holds splatted depths nearer than `nearest` at all its pixels.
bool behind_tiles(ivec2 lo, ivec2 hi, float nearest)
{
    ivec2 first = tile_of(lo), last = tile_of(hi);
    for (int ty = first.y; ty <= last.y; ty++)
        for (int tx = first.x; tx <= last.x; tx++)
            if (uintBitsToFloat(imageLoad(far_tiles, ivec2(tx, ty)).r) >= nearest)
                return false;
    return true;
}

bool walked_in_this_phase(vec3 centre, float depth, float reach, ivec2 lo, ivec2 hi)
{
    if (cull_phase == CULL_NONE)
        return true;
    bool near = near_front(centre, depth, reach);
    if (cull_phase == CULL_NEAR)
        return near;
    // No point of the sphere (or of the ellipsoid inside it) is nearer than depth - reach.
    return !near && !behind_tiles(lo, hi, depth - reach);
}
#endif

#ifdef FC_FUSED_THICKNESS
// The camera's thickness at a reduced scale in the depth's own walk over the
// particles (compute_splat.c: spheres whose thickness takes the footprint):
// on llvmpipe a particle's invocation, load and transform cost more than its
// footprint (a dispatch that only loads a million particles is about a third
// of the thickness splat, bench/RESULTS.md), so the thickness rides along in
// the phase that sees every particle once, at its own resolution: the same
// pixels and sums as the thickness-only splat of that view.
layout(location = 13) uniform vec2 thickness_viewport;   // pixels of the thickness image

void splat_footprint(vec2 x_range, vec2 y_range, vec3 centre, float reach)
{
    splat_footprint_into(x_range, y_range, reach, volume_above_floor(centre, reach), thickness_viewport, false);
}
#endif

#ifdef FC_FUSED_SUN
// The shadow map's thickness in the same walk as well (compute_splat.c:
// fc_compute_splat_run_fused with a sun): the particle seen from the sun's
// camera (shadow_pass.c), without a floor, at its map's thickness
// resolution. The same pixels and sums as that view's thickness-only splat
// with the footprint, for the same reason as the camera's thickness above.
// Only where the sun sees sprites of at most 2x2 pixels (compute_splat.c):
// with larger ones the fused walk cost more than the sun's own splat.
layout(location = 15) uniform mat4 sun_matrix;      // world -> the sun's view (locations 15-18)
layout(location = 19) uniform vec2 sun_focal;       // its P[0][0], P[1][1]
layout(location = 20) uniform vec2 sun_viewport;    // pixels of the sun's thickness image

void splat_sun_footprint(float reach)
{
    vec3 centre = (sun_matrix * vec4(loaded_world_centre(), 1.0)).xyz;
    float depth = -centre.z;
    if (depth <= 0.0)   // as the sun's own splat: its camera holds every particle in front
        return;
    vec2 x_range = projected_interval(centre.x, depth, sun_focal.x, reach);
    vec2 y_range = projected_interval(centre.y, depth, sun_focal.y, reach);
    splat_footprint_into(x_range, y_range, reach, 1.0, sun_viewport, true);
}
#endif

void main()
{
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (i >= particle_count)
        return;
    vec4 particle = load_particle(i);
    vec3 centre = particle.xyz;
    float reach = particle.w;   // the bounding sphere's radius
    float depth = -centre.z;
#ifdef FC_FUSED_SUN
    // Before the camera's tests: the sun sees particles behind the camera too.
    if (cull_phase != CULL_NEAR)
        splat_sun_footprint(reach);
#endif
    // A centre behind the eye: the fragment splat culls its sprite too.
    if (depth <= 0.0)
        return;
    // An ellipsoid's exact box where it has one; the row spans below stay
    // those of its bounding sphere, clipped to the box.
    vec4 box;
    bool exact = particle_ndc_bounds(centre, projection.xy, box);
    vec2 x_range = exact ? box.xy : projected_interval(centre.x, depth, projection.x, reach);
    vec2 y_range = exact ? box.zw : projected_interval(centre.y, depth, projection.y, reach);
    // The pixels whose centres lie within the bounds, grown by the fragment
    // splat's margin (sphere.vert.glsl), clipped to the image. Walking one
    // more pixel per side and axis, as a plain floor and ceil of the bounds
    // would, quadruples the pixels of a one-pixel sphere.
    vec2 first = (vec2(x_range.x, y_range.x) + 1.0) * 0.5 * viewport - 0.5 - MARGIN_PIXELS;
    vec2 last = (vec2(x_range.y, y_range.y) + 1.0) * 0.5 * viewport - 0.5 + MARGIN_PIXELS;
    ivec2 lo = max(ivec2(ceil(first)), ivec2(0));
    ivec2 hi = min(ivec2(floor(last)), ivec2(viewport) - 1);
#ifdef FC_THICKNESS_FOOTPRINT
    splat_footprint_into(x_range, y_range, reach, volume_above_floor(centre, reach), viewport, false);
#else
#ifdef FC_THICKNESS_ONLY
    particle_above_floor = volume_above_floor(centre, reach);
#endif
#ifdef FC_DEPTH_ONLY
    if (walked_in_this_phase(centre, depth, reach, lo, hi))
#endif
        walk_pixels(lo, hi, centre, reach);
#endif
#ifdef FC_FUSED_THICKNESS
    if (cull_phase != CULL_NEAR)
        splat_footprint(x_range, y_range, centre, reach);
#endif
}
