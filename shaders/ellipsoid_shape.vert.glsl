#version 450 core
// The particle as its anisotropic ellipsoid (anisotropy.h): the vertex side
// of an ellipsoid sprite (sphere.vert.glsl). The sprite bounds the
// ellipsoid's bounding sphere, radius x its longest stretch; the fragments
// get the ellipsoid's G in view space, once per particle rather than per
// pixel.

layout(location = 0) uniform mat4 view_matrix;
layout(location = 3) uniform float radius;   // world units

struct ellipsoid {
    vec4 centre_stretch;   // smoothed world centre; longest axis in radii, 1 exactly for a sphere
    vec4 inverse_a;        // G xx, xy, xz, yy (world space)
    vec4 inverse_b;        // G yz, zz; neighbours; unused
};
layout(std430, binding = 5) readonly buffer Ellipsoids { ellipsoid ellipsoids[]; };

layout(location = 2) flat out mat3 ellipsoid_inverse;   // G in view space (locations 2-4)
layout(location = 5) flat out float ellipsoid_stretch;

// G of a world-space ellipsoid in view space: |G (x - c)| is a length, and
// rotating it by the view's rotation V changes nothing, so G_view = V G V^T.
mat3 view_inverse(ellipsoid e)
{
    vec4 a = e.inverse_a;
    vec4 b = e.inverse_b;
    mat3 g = mat3(a.x, a.y, a.z, a.y, a.w, b.x, a.z, b.x, b.y);
    mat3 rotation = mat3(view_matrix);
    return rotation * g * transpose(rotation);
}

vec4 particle_bounds(int slot, vec3 position)
{
    ellipsoid e = ellipsoids[slot];
    ellipsoid_inverse = view_inverse(e);
    ellipsoid_stretch = e.centre_stretch.w;
    return vec4(e.centre_stretch.xyz, radius * e.centre_stretch.w);
}
