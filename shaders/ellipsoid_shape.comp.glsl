#version 450 core
// The particle as its anisotropic ellipsoid (anisotropy.h), for the compute
// splat (surface_splat.comp.glsl): the smoothed centre, the bounding sphere
// the walk covers (radius x the longest stretch), and the ray cast, the
// sphere's own for a particle the anisotropy left a sphere.

bool cast_sphere_ray(vec2 pixel, vec3 centre, float radius, out float depth, out float chord);
bool cast_ellipsoid_ray(vec2 pixel, vec3 centre, mat3 inverse, float radius, out float depth, out float chord);
bool projected_ellipsoid_bounds(vec3 centre, mat3 a, vec2 focal, out vec4 box);

layout(location = 0) uniform mat4 view_matrix;    // world -> view
layout(location = 3) uniform float radius;            // world units: every particle's, or the median's
layout(location = 9) uniform uint first_particle;     // draw slot of the dispatch's first particle
layout(location = 512) uniform bool sized_particles;   // each particle's radius is radius x its ratio

layout(binding = 1) uniform samplerBuffer radius_ratios;   // R32F: the dispatch's particles' ratios

struct ellipsoid {
    vec4 centre_stretch;   // smoothed world centre; longest axis in radii, 1 exactly for a sphere
    vec4 inverse_a;        // G xx, xy, xz, yy (world space)
    vec4 inverse_b;        // G yz, zz; neighbours; unused
};
layout(std430, binding = 5) readonly buffer Ellipsoids { ellipsoid ellipsoids[]; };

// The loaded particle's G in view space (see ellipsoid_shape.vert.glsl), stretch and radius.
mat3 particle_inverse;
float particle_stretch;
float loaded_radius;

vec4 load_particle(uint i)
{
    ellipsoid e = ellipsoids[first_particle + i];
    vec4 a = e.inverse_a;
    vec4 b = e.inverse_b;
    mat3 rotation = mat3(view_matrix);
    particle_inverse = rotation * mat3(a.x, a.y, a.z, a.y, a.w, b.x, a.z, b.x, b.y) * transpose(rotation);
    particle_stretch = e.centre_stretch.w;
    // An `if` on the uniform, not a selection, which llvmpipe evaluated in
    // full: the fetch ran for spheres of one size too (2% of the instructions
    // of a 1M-particle frame, bench/RESULTS.md).
    loaded_radius = radius;
    if (sized_particles)
        loaded_radius *= texelFetch(radius_ratios, int(i)).r;
    return vec4((view_matrix * vec4(e.centre_stretch.xyz, 1.0)).xyz, loaded_radius * particle_stretch);
}

bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord)
{
    if (particle_stretch == 1.0)
        return cast_sphere_ray(pixel, centre, loaded_radius, depth, chord);
    return cast_ellipsoid_ray(pixel, centre, particle_inverse, loaded_radius, depth, chord);
}

// The exact NDC box of the loaded ellipsoid (see ellipsoid_shape.vert.glsl).
bool particle_ndc_bounds(vec3 view_centre, vec2 focal, out vec4 box)
{
    box = vec4(0.0);
    return particle_stretch != 1.0 &&
           projected_ellipsoid_bounds(view_centre, loaded_radius * inverse(particle_inverse), focal, box);
}
