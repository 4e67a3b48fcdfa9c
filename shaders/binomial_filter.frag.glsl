#version 450 core
// One 1-D pass of the Instant Liquids smoothing (Cords & Staadt, §2.2 and §3):
// iterated separable binomial kernels of half-width k, with the silhouette map.
//
// In the paper the background holds the far depth, so smoothing spreads the
// fluid over the background around it; the silhouette map (the binary "has
// fluid" image of the smoothed depth, smoothed by the same kernel) keeps the
// fluid only where it reaches 1. Together that is a morphological closing of
// the fluid's outline: notches and gaps narrower than the kernel fill, the
// skirt that smoothing drags out of the silhouette is cut away again. Here the
// background is 0, not far, so the spreading is done explicitly (normalized
// convolution over fluid neighbours, carrying their weight as coverage), and
// neighbours beyond the depth jump are left out so separate surfaces never
// blend. The map reads "1" and "has fluid" at the resolution of an 8-bit map
// (EPSILON) rather than exactly, which keeps the closing to the kernel's
// effective reach instead of its full support; pixels that held fluid before
// smoothing are kept whatever the map says, as an exact closing would.
//
// Texels: (depth, coverage or map, 1 where the pixel held fluid before, unused).
// Phases, one uniform per pass (see binomial_filter.c):
//   SMOOTH_FROM_DEPTH  first pass: input is raw depth, coverage 1 where z > 0
//   SMOOTH             smooths depth and coverage
//   SILHOUETTE_START   binarizes coverage (> EPSILON) and smooths it into the map
//   SILHOUETTE         smooths the map further
//   SILHOUETTE_FINISH  as SILHOUETTE, then keeps depth only where the map is 1
//                      or the pixel held fluid before

struct surface_walk {
    float last;
    bool ended;
};
surface_walk walk_from(float z);
bool walk_accepts(inout surface_walk walk, float zi);
bool on_grid(ivec2 p);
ivec2 nearest_on_grid(ivec2 p);
vec4 texel_at(ivec2 p);

layout(location = 0) uniform ivec2 axis;
layout(location = 3) uniform float depth_jump;
layout(location = 4) uniform int fixed_radius;   // k, always set by binomial_filter.c
layout(location = 6) uniform int phase;

layout(location = 0) out vec4 result;

const int SMOOTH_FROM_DEPTH = 0;
const int SMOOTH = 1;
const int SILHOUETTE_START = 2;
const int SILHOUETTE = 3;
const int SILHOUETTE_FINISH = 4;

// What "equal to one" means for the map, and "has fluid" for the coverage:
// the resolution of an 8-bit map, as in the paper.
const float EPSILON = 1.0 / 256.0;

// Depth, coverage and "held fluid before" of a texel in the current phase's convention.
vec3 depth_coverage_original(ivec2 q)
{
    vec3 t = texel_at(q).rgb;
    float fluid = t.r > 0.0 ? 1.0 : 0.0;
    return phase == SMOOTH_FROM_DEPTH ? vec3(t.r, fluid, fluid) : t;
}

vec2 depth_and_coverage(ivec2 q)
{
    return depth_coverage_original(q).xy;
}

// C(2R, R) / 4^R: the centre's weight in the normalized kernel, by which the
// weights relative to it (C(2R, R + i) / C(2R, R)) are scaled back.
float central_binomial(int radius)
{
    float c = 1.0;
    for (int k = 1; k <= radius; k++)
        c *= float(2 * k - 1) / float(2 * k);
    return c;
}

// Binomial weights C(2R, R + i) / C(2R, R) times coverage, summed over one side of the
// kernel along the centre's surface (surface_walk).
struct side_sums {
    float weighted_depth;
    float coverage;
    float first_depth;   // of the nearest sample on the surface, 0 when none
};

side_sums side_of(ivec2 p, float z, int radius, int direction)
{
    side_sums sums = side_sums(0.0, 0.0, 0.0);
    surface_walk walk = walk_from(z);
    float binomial = 1.0;   // C(2R, R + i) / C(2R, R), updated from i - 1
    for (int i = 1; i <= radius && !walk.ended; i++) {
        binomial *= float(radius - i + 1) / float(radius + i);
        ivec2 q = p + direction * i * axis;
        if (!on_grid(q))
            break;
        vec2 dc = depth_and_coverage(q);
        if (!walk_accepts(walk, dc.x))
            continue;
        sums.first_depth = sums.first_depth > 0.0 ? sums.first_depth : dc.x;
        sums.weighted_depth += binomial * dc.y * dc.x;
        sums.coverage += binomial * dc.y;
    }
    return sums;
}

// Normalized binomial convolution over the samples on the centre's surface;
// the coverage is the kernel weight they carry. A pixel without fluid is
// spread onto from the nearer of the surfaces on its two sides, as a pixel
// shows the nearest surface.
vec4 smooth_depth(ivec2 p, int radius)
{
    vec3 centre = depth_coverage_original(p);
    side_sums forward = side_of(p, centre.x, radius, 1);
    side_sums backward = side_of(p, centre.x, radius, -1);
    if (centre.x <= 0.0 && forward.coverage > 0.0 && backward.coverage > 0.0 &&
        abs(forward.first_depth - backward.first_depth) > depth_jump) {
        if (forward.first_depth < backward.first_depth)
            backward = side_sums(0.0, 0.0, 0.0);
        else
            forward = side_sums(0.0, 0.0, 0.0);
    }
    float weighted_depth = centre.y * centre.x + forward.weighted_depth + backward.weighted_depth;
    float coverage = centre.y + forward.coverage + backward.coverage;
    if (coverage <= 0.0)
        return vec4(0.0);
    return vec4(weighted_depth / coverage, coverage * central_binomial(radius), centre.z, 0.0);
}

// A value of the silhouette map in this phase: the first silhouette pass
// turns coverage into the binary "has fluid" image.
float silhouette_value(vec4 t)
{
    return phase == SILHOUETTE_START ? (t.g > EPSILON ? 1.0 : 0.0) : t.g;
}

// The silhouette map, smoothed by the same kernel. Off the grid the edge texel
// is repeated: fluid that leaves the image has no silhouette there.
vec4 smooth_silhouette(ivec2 p, int radius)
{
    vec4 centre = texel_at(p);
    float binomial = 1.0, map = silhouette_value(centre);
    for (int i = 1; i <= radius; i++) {
        binomial *= float(radius - i + 1) / float(radius + i);
        map += binomial * (silhouette_value(texel_at(nearest_on_grid(p + i * axis))) +
                           silhouette_value(texel_at(nearest_on_grid(p - i * axis))));
    }
    map *= central_binomial(radius);
    bool held_fluid = centre.b > 0.0;
    if (phase == SILHOUETTE_FINISH && map < 1.0 - EPSILON && !held_fluid)
        centre.r = 0.0;
    return vec4(centre.r, map, centre.b, 0.0);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    // One kernel size k for the whole image, as in the paper.
    int radius = fixed_radius;
    result = phase <= SMOOTH ? smooth_depth(p, radius) : smooth_silhouette(p, radius);
}
