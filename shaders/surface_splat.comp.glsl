#version 450 core
// Depth and thickness of the spheres (or ellipsoids, walked over their
// bounding spheres) in one splat, like surface_splat.frag.glsl
// but without the rasterizer: one invocation per particle walks the pixels of
// its sphere's projected bounding box (sphere_bounds.glsl), row by row over
// the columns the silhouette can reach, and ray-casts each (sphere_ray.glsl,
// thickness_chord.glsl: the fragment splat's arithmetic, so both find the
// same pixels and depths).
// The nearest depth wins by imageAtomicMin on the float's bits, which order
// like the floats because depths are positive; thickness is summed by
// imageAtomicAdd in fixed point (llvmpipe's GL has no float image atomics).
// Atomics on storage buffers instead of images measured no faster on
// llvmpipe (bench/RESULTS.md, fifth round).
// surface_resolve.comp.glsl turns both into the fragment splat's images.
// Faster on llvmpipe for small sprites, where a point sprite's set-up costs
// more than its few pixels (bench/RESULTS.md, third round); depth_pass.c
// chooses.

// The particle's shape, sphere or ellipsoid (sphere_shape.comp.glsl,
// ellipsoid_shape.comp.glsl): its view-space centre and bounding radius, and
// the ray cast.
vec4 load_particle(uint i);
bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord);
float thickness_above_floor(vec2 pixel, float depth, float chord);
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
    uint bits = floatBitsToUint(depth);
    if (ndc_z >= -1.0 && bits < imageLoad(nearest_depth, p).r)
        imageAtomicMin(nearest_depth, p, bits);
    if (units_per_chord > 0.0) {
        float share = min(thickness_above_floor(pixel, depth, chord) / max_chord, 1.0);
        imageAtomicAdd(thickness_sum, p, uint(share * units_per_chord + 0.5));
    }
}

// The columns of row y whose rays may meet the sphere, within [lo, hi]: the
// walk skips the corners of the bounding box. A ray d = (a, v, -1) (a, v:
// the pixel centre's NDC over the focal lengths) meets the sphere where
// (d·c)² >= |d|² k, k = |c|² - r²: for a fixed row a quadratic in a,
// qa a² + 2 qb a + qc >= 0, whose discriminant works out to
// k (r² (1 + v²) - (c.y + v c.z)²), free of the cancellation the textbook
// form suffers. It lies between its roots when it opens downwards (qa < 0),
// as it does unless the eye is inside the sphere's tangent cylinder along x.
// A row the sphere only grazes keeps the column where it would touch, and
// the quarter pixel of margin on each side absorbs rounding (a few hundredths
// of a pixel even at the widest sprites): the ray cast decides each pixel,
// the span must only hold every one it could accept.
ivec2 row_span(int y, vec3 centre, float radius, ivec2 lo, ivec2 hi)
{
    float v = ((float(y) + 0.5) / viewport.y * 2.0 - 1.0) / projection.y;
    float r2 = radius * radius;
    float qa = r2 - centre.y * centre.y - centre.z * centre.z;
    float k = dot(centre, centre) - r2;
    if (qa >= 0.0 || k <= 0.0)
        return ivec2(lo.x, hi.x);
    float qb = centre.x * (v * centre.y - centre.z);
    float across = centre.y + v * centre.z;
    float root = sqrt(k * max(r2 * (1.0 + v * v) - across * across, 0.0));
    vec2 a = vec2(-qb + root, -qb - root) / qa;   // ascending: qa < 0
    vec2 x = (a * projection.x + 1.0) * 0.5 * viewport.x - 0.5;
    return ivec2(max(lo.x, int(ceil(x.x - MARGIN_PIXELS))), min(hi.x, int(floor(x.y + MARGIN_PIXELS))));
}

void main()
{
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (i >= particle_count)
        return;
    vec4 particle = load_particle(i);
    vec3 centre = particle.xyz;
    float reach = particle.w;   // the bounding sphere's radius
    float depth = -centre.z;
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
    for (int y = lo.y; y <= hi.y; y++) {
        ivec2 span = row_span(y, centre, reach, lo, hi);
        for (int x = span.x; x <= span.y; x++)
            splat_pixel(ivec2(x, y), centre);
    }
}
