#version 450 core
// The fluid surface's shading normal at a pixel (van der Laan et al. 2009,
// §3.5): from finite differences of the smoothed depth, one-sided at
// discontinuities, then tilted by the slope of the surface noise N. Linked
// into the composite and the normal AOV programs.

vec3 view_ray(vec2 window);

layout(binding = 0) uniform sampler2D surface_depth;   // smoothed linear depth, 0 = no fluid
layout(binding = 3) uniform sampler2D surface_noise;   // N(x, y) of noise.frag.glsl, 0 = none

layout(location = 0) uniform vec2 focal;               // P[0][0], P[1][1]
layout(location = 5) uniform vec2 viewport;
layout(location = 12) uniform float particle_radius;   // world units
#ifdef FC_VARIANT
const bool has_noise = FC_HAS_NOISE != 0;                   // shader_variants.h
#else
layout(location = 19) uniform bool has_noise;          // false: N is 0 everywhere and is not read
#endif
layout(location = 42) uniform ivec2 surface_size;      // the image in use, within the texture

float depth_at(ivec2 p)
{
    ivec2 size = surface_size;
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size)))
        return 0.0;
    return texelFetch(surface_depth, p, 0).r;
}

// Only ever asked for fluid pixels, which are on screen.
float noise_at(ivec2 p)
{
    return texelFetch(surface_noise, p, 0).r;
}

vec3 view_point(ivec2 p, float z)
{
    return view_ray(vec2(p) + 0.5) * z;
}

// The neighbours along `axis` a finite difference at p spans: (ahead,
// behind), each 0 or 1 pixel. Central where both continue the surface (a
// step of less than a particle radius); at a discontinuity the side with the
// smaller step (§3.5), since the other side is another surface or background
// and would bend the normal there.
ivec2 difference_span(ivec2 p, ivec2 axis, float z)
{
    float z_fwd = depth_at(p + axis);
    float z_bwd = depth_at(p - axis);
    bool fwd = z_fwd > 0.0;
    bool bwd = z_bwd > 0.0;
    float step_fwd = abs(z_fwd - z), step_bwd = abs(z - z_bwd);
    if (fwd && bwd && max(step_fwd, step_bwd) >= particle_radius) {
        fwd = step_fwd <= step_bwd;
        bwd = !fwd;
    }
    return ivec2(fwd ? 1 : 0, bwd ? 1 : 0);
}

// The spans of both axes at a pixel, found once: the normal, the noise
// slope and inside_surface all need them, and each costs four depth fetches.
struct surface_spans {
    ivec2 x;
    ivec2 y;
};

surface_spans spans_at(ivec2 p, float z)
{
    return surface_spans(difference_span(p, ivec2(1, 0), z), difference_span(p, ivec2(0, 1), z));
}

// Whether the surface continues to all four neighbours: where it does not,
// the normal comes from one-sided differences across a sphere's rim and is
// only a guess.
bool inside_surface(surface_spans spans)
{
    return spans.x.x + spans.x.y + spans.y.x + spans.y.y == 4;
}

vec3 surface_tangent(ivec2 p, ivec2 axis, ivec2 span, vec3 centre)
{
    ivec2 ahead = p + span.x * axis, behind = p - span.y * axis;
    vec3 a = span.x > 0 ? view_point(ahead, depth_at(ahead)) : centre;
    vec3 b = span.y > 0 ? view_point(behind, depth_at(behind)) : centre;
    return a - b;
}

vec3 surface_normal(ivec2 p, vec3 centre, surface_spans spans)
{
    vec3 n = cross(surface_tangent(p, ivec2(1, 0), spans.x, centre), surface_tangent(p, ivec2(0, 1), spans.y, centre));
    float len = length(n);
    if (len == 0.0)
        return vec3(0.0, 0.0, 1.0);   // an isolated pixel: assume it faces the camera
    n /= len;
    return dot(n, centre) > 0.0 ? -n : n;   // towards the camera at the origin
}

// dN per pixel along `axis`, over the same span as the surface tangent, so
// the noise outside the fluid (0) never enters.
float noise_slope(ivec2 p, ivec2 axis, ivec2 span)
{
    if (span.x + span.y == 0)
        return 0.0;
    return (noise_at(p + span.x * axis) - noise_at(p - span.y * axis)) / float(span.x + span.y);
}

// N is a height field in particle radii over the surface (the patent adds its
// partial derivatives to the normal): its world-space slope is dN/dpixel
// times the radius times the pixels per world unit at this depth.
vec3 shading_normal(ivec2 p, vec3 centre, float z, surface_spans spans)
{
    vec3 n = surface_normal(p, centre, spans);
    if (!has_noise)
        return n;
    vec2 pixels_per_unit = 0.5 * viewport * focal / z;
    vec2 slope = vec2(noise_slope(p, ivec2(1, 0), spans.x), noise_slope(p, ivec2(0, 1), spans.y)) * particle_radius *
                 pixels_per_unit;
    return normalize(n - vec3(slope, 0.0));
}
