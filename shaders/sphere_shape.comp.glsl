#version 450 core
// The particle as a sphere, for the compute splat (surface_splat.comp.glsl):
// where it is and how to cast it (ellipsoid_shape.comp.glsl is the anisotropic
// one).

bool cast_sphere_ray(vec2 pixel, vec3 centre, float radius, out float depth, out float chord);

layout(location = 0) uniform mat4 view_matrix;        // world -> view
layout(location = 3) uniform float radius;            // world units: every particle's, or the median's
layout(location = 512) uniform bool sized_particles;   // each particle's radius is radius x its ratio

// A buffer texture, not a storage buffer: llvmpipe gathers a texel fetch
// for all lanes at once but loads from a storage buffer lane by lane.
layout(binding = 0) uniform samplerBuffer particle_positions;   // RGB32F: xyz per particle, world space
layout(binding = 1) uniform samplerBuffer radius_ratios;        // R32F: the dispatch's particles' ratios

// The loaded particle's radius and world-space centre.
float loaded_radius;
vec3 loaded_world;

// The view-space centre and bounding radius of the dispatch's particle i.
vec4 load_particle(uint i)
{
    // An `if` on the uniform, not a selection, which llvmpipe evaluated in
    // full: the fetch ran for spheres of one size too (2% of the instructions
    // of a 1M-particle frame, bench/RESULTS.md).
    loaded_radius = radius;
    if (sized_particles)
        loaded_radius *= texelFetch(radius_ratios, int(i)).r;
    loaded_world = texelFetch(particle_positions, int(i)).xyz;
    return vec4((view_matrix * vec4(loaded_world, 1.0)).xyz, loaded_radius);
}

// The loaded particle's centre in world space (for a second view of it, FC_FUSED_SUN).
vec3 loaded_world_centre()
{
    return loaded_world;
}

bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord)
{
    return cast_sphere_ray(pixel, centre, loaded_radius, depth, chord);
}

// Spheres take their NDC bounds from sphere_bounds.glsl's intervals.
bool particle_ndc_bounds(vec3 view_centre, vec2 focal, out vec4 box)
{
    box = vec4(0.0);
    return false;
}
