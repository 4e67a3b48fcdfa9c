#version 450 core
// The particle as its anisotropic ellipsoid, fragment side
// (ellipsoid_shape.vert.glsl passes it on): the shape the splats' fragment
// shaders cast and shade. A particle the anisotropy left a sphere casts the
// sphere's own ray, so it is today's sphere bit for bit.

bool cast_sphere_ray(vec2 pixel, vec3 centre, float radius, out float depth, out float chord);
bool cast_ellipsoid_ray(vec2 pixel, vec3 centre, mat3 inverse, float radius, out float depth, out float chord);

layout(location = 2) flat in mat3 ellipsoid_inverse;   // view space
layout(location = 5) flat in float ellipsoid_stretch;  // 1 exactly: a sphere
layout(location = 6) flat in float splat_radius;       // this particle's radius, world units

bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord)
{
    if (ellipsoid_stretch == 1.0)
        return cast_sphere_ray(pixel, centre, splat_radius, depth, chord);
    return cast_ellipsoid_ray(pixel, centre, ellipsoid_inverse, splat_radius, depth, chord);
}

// The outward unit normal at `hit` on the surface (view space): the
// gradient of |G (x - c)|^2, G^T G (x - c), with G symmetric.
vec3 particle_normal(vec3 hit, vec3 centre)
{
    if (ellipsoid_stretch == 1.0)
        return (hit - centre) / splat_radius;
    return normalize(ellipsoid_inverse * (ellipsoid_inverse * (hit - centre)));
}
