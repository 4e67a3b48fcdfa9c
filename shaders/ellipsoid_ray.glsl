#version 450 core
// Ray-casts an ellipsoid at a pixel centre: the points x with
// |G (x - centre)| <= radius, G symmetric, in view space (anisotropy.h). The
// view ray is taken into the space where the ellipsoid is the sphere of the
// radius, and solved there as sphere_ray.glsl solves a sphere (the miss
// distance from the closest point, free of cancellation). A library without
// a stage, linked after sphere_ray.glsl into the fragment splats and the
// compute splat.

vec3 pixel_ray(vec2 pixel);

// False when the view ray through `pixel` misses the ellipsoid of `radius`
// (the particle's own). Otherwise
// `depth` is the linear view depth of the front hit and `chord` the length of
// the ray inside the ellipsoid (world units).
bool cast_ellipsoid_ray(vec2 pixel, vec3 centre, mat3 inverse, float radius, out float depth, out float chord)
{
    vec3 dir = pixel_ray(pixel);
    // Along the ray x(t) = t dir the transformed point is t a - b.
    vec3 a = inverse * dir;
    vec3 b = inverse * centre;
    float t_closest = dot(a, b) / dot(a, a);
    vec3 miss = b - t_closest * a;
    float half_chord_sq = radius * radius - dot(miss, miss);
    if (half_chord_sq <= 0.0) {
        depth = 0.0;
        chord = 0.0;
        return false;
    }
    float half_depth = sqrt(half_chord_sq) / length(a);   // half the chord in units of t, linear depth
    depth = t_closest - half_depth;
    chord = 2.0 * half_depth * length(dir);
    return true;
}
