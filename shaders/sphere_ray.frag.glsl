#version 450 core
// Ray-casts a particle's sphere at this fragment's pixel centre; linked into
// the depth and thickness programs together with sphere.vert.glsl.

layout(location = 1) uniform vec4 projection;   // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;
layout(location = 3) uniform float radius;

// False when the view ray through this pixel misses the sphere. Otherwise
// `depth` is the linear view depth of the front hit and `chord` the length of
// the ray inside the sphere (world units).
bool cast_sphere_ray(vec3 centre, out float depth, out float chord)
{
    vec2 ndc = gl_FragCoord.xy / viewport * 2.0 - 1.0;
    // With dir.z = -1 the ray parameter is the linear depth itself.
    vec3 dir = vec3(ndc / projection.xy, -1.0);
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
