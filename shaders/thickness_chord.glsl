#version 450 core
// The part of a sphere's chord that counts as thickness (van der Laan et al.
// 2009, §3.3, eq. 9). The paper depth-tests against the scene; the only
// opaque scene geometry is the floor, a plane, so the chord is clipped
// against it exactly instead: fluid below the floor does not count. A library
// without a stage, linked into the thickness splat and both surface splats
// (fragment and compute) after sphere_ray.glsl.

vec3 pixel_ray(vec2 pixel);

layout(location = 10) uniform vec4 floor_plane;  // view space: dot(xyz, x) + w > 0 above; (0,0,0,1) = none

// Length (world units) of the view ray through `pixel` inside the sphere it
// meets at linear `depth` with a chord of `chord`, above the floor; 0 when
// none is.
float thickness_above_floor(vec2 pixel, float depth, float chord)
{
    // Along the ray x(t) = t·dir (t is linear depth) the height above the
    // floor is rate·t + w: the part with positive height counts.
    vec3 dir = pixel_ray(pixel);
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

// The fraction of a sphere's volume above the floor: a cap of height r + h
// for a centre at height h, (r + h)^2 (2r - h) / 4r^3 of the volume. Over
// the image the thickness of all rays through a sphere integrates to its
// volume, so this is the clipped chords' share in total.
float volume_above_floor(vec3 centre, float radius)
{
    if (floor_plane.xyz == vec3(0.0))   // no floor: all above, or (w <= 0) all below as thickness_above_floor
        return floor_plane.w > 0.0 ? 1.0 : 0.0;
    float height = (dot(floor_plane.xyz, centre) + floor_plane.w) / length(floor_plane.xyz);
    float t = clamp(height / radius, -1.0, 1.0);
    return (1.0 + t) * (1.0 + t) * (2.0 - t) * 0.25;
}
