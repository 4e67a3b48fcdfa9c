#version 450 core
// The particle as its anisotropic ellipsoid (anisotropy.h): the vertex side
// of an ellipsoid sprite (sphere.vert.glsl). The sprite bounds the
// ellipsoid's bounding sphere, radius x its longest stretch; the fragments
// get the ellipsoid's G in view space, once per particle rather than per
// pixel. With per-particle radii the particle's radius (as sphere_shape.vert.glsl
// chooses it) scales its ellipsoid: twice the median radius, twice as large.

layout(location = 0) uniform mat4 view_matrix;
layout(location = 3) uniform float radius;            // world units: every particle's, or the median's
layout(location = 512) uniform bool sized_particles;   // each particle's radius is radius x its ratio
layout(std430, binding = 7) readonly buffer RadiusRatios { float radius_ratios[]; };   // per draw slot

struct ellipsoid {
    vec4 centre_stretch;   // smoothed world centre; longest axis in radii, 1 exactly for a sphere
    vec4 inverse_a;        // G xx, xy, xz, yy (world space)
    vec4 inverse_b;        // G yz, zz; neighbours; unused
};
layout(std430, binding = 5) readonly buffer Ellipsoids { ellipsoid ellipsoids[]; };

bool projected_ellipsoid_bounds(vec3 centre, mat3 a, vec2 focal, out vec4 box);

layout(location = 2) flat out mat3 ellipsoid_inverse;   // G in view space (locations 2-4)
layout(location = 5) flat out float ellipsoid_stretch;
layout(location = 6) flat out float splat_radius;     // this particle's radius, world units

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

// The particle's G, stretch and radius in view space, kept for particle_ndc_bounds.
mat3 view_g;
float stretch;
float own_radius;

vec4 particle_bounds(int slot, vec3 position)
{
    ellipsoid e = ellipsoids[slot];
    view_g = view_inverse(e);
    stretch = e.centre_stretch.w;
    ellipsoid_inverse = view_g;
    ellipsoid_stretch = stretch;
    own_radius = sized_particles ? radius * radius_ratios[slot] : radius;
    splat_radius = own_radius;
    return vec4(e.centre_stretch.xyz, own_radius * stretch);
}

// The exact NDC box of the ellipsoid (ellipsoid_bounds.glsl): a needle or a
// disc seen edge-on covers a fraction of its bounding sphere's box. False
// for a sphere (its own intervals, bit for bit) and for an ellipsoid reaching
// the eye's plane (the bounding sphere's, clamped).
bool particle_ndc_bounds(vec3 view_centre, vec2 focal, out vec4 box)
{
    box = vec4(0.0);
    return stretch != 1.0 && projected_ellipsoid_bounds(view_centre, own_radius * inverse(view_g), focal, box);
}
