#version 450 core
// The part of a sphere's chord that counts as thickness (van der Laan et al.
// 2009, §3.3, eq. 9). The paper depth-tests against the scene; the only
// opaque scene geometry is the floor, a plane, so the chord is clipped
// against it exactly instead: fluid below the floor does not count. Linked
// into the thickness and surface splat programs.

layout(location = 1) uniform vec4 projection;    // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;
layout(location = 10) uniform vec4 floor_plane;  // view space: dot(xyz, x) + w > 0 above; (0,0,0,1) = none

// Length (world units) of this pixel's view ray inside the sphere it meets at
// linear `depth` with a chord of `chord`, above the floor; 0 when none is.
float thickness_above_floor(float depth, float chord)
{
    // Along the ray x(t) = t·dir (t is linear depth) the height above the
    // floor is rate·t + w: the part with positive height counts.
    vec3 dir = vec3((gl_FragCoord.xy / viewport * 2.0 - 1.0) / projection.xy, -1.0);
    float len = length(dir);
    float near = depth, far = depth + chord / len;
    float rate = dot(floor_plane.xyz, dir);
    if (rate < 0.0)
        far = min(far, -floor_plane.w / rate);
    else if (rate > 0.0)
        near = max(near, -floor_plane.w / rate);
    else if (floor_plane.w <= 0.0)
        return 0.0;
    return far > near ? (far - near) * len : 0.0;
}
