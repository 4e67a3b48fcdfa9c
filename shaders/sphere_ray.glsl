#version 450 core
// Ray-casts a particle's sphere at a pixel centre. A library without a stage:
// linked into the fragment splats (with gl_FragCoord.xy) and into the compute
// splat (surface_splat.comp.glsl, with the pixels it walks), so both splats
// find the same sphere surface.

layout(location = 1) uniform vec4 projection;   // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;

// The view ray through `pixel` (window coordinates of a pixel centre, origin
// at the lower left) with dir.z = -1, so the ray parameter is linear depth.
vec3 pixel_ray(vec2 pixel)
{
    return vec3((pixel / viewport * 2.0 - 1.0) / projection.xy, -1.0);
}

// False when the view ray through `pixel` misses the sphere of `radius`
// (world units: the particle's own, sphere_shape.*.glsl). Otherwise
// `depth` is the linear view depth of the front hit and `chord` the length of
// the ray inside the sphere (world units).
bool cast_sphere_ray(vec2 pixel, vec3 centre, float radius, out float depth, out float chord)
{
    vec3 dir = pixel_ray(pixel);
    float t_closest = dot(dir, centre) / dot(dir, dir);
    // Measuring the miss distance from the closest point, rather than solving
    // the quadratic directly, avoids cancelling two large numbers when the
    // sphere is small and far away.
    vec3 miss = centre - t_closest * dir;
    float half_chord_sq = radius * radius - dot(miss, miss);
    if (half_chord_sq <= 0.0) {
        depth = 0.0;
        chord = 0.0;
        return false;
    }
    float half_chord = sqrt(half_chord_sq);
    depth = t_closest - half_chord / length(dir);
    chord = 2.0 * half_chord;
    return true;
}
