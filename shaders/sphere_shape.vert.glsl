#version 450 core
// The particle as a sphere at its position: the vertex side of a sphere
// sprite (sphere.vert.glsl). Its radius is the uniform one, or with
// per-particle radii (particle_buffer.h) the uniform times the particle's
// ratio to the frame's median; the fragments get it as splat_radius.

layout(location = 3) uniform float radius;            // world units: every particle's, or the median's
layout(location = 512) uniform bool sized_particles;   // each particle's radius is radius x its ratio
layout(std430, binding = 7) readonly buffer RadiusRatios { float radius_ratios[]; };   // per draw slot

layout(location = 6) flat out float splat_radius;     // this particle's radius, world units

vec4 particle_bounds(int slot, vec3 position)
{
    splat_radius = sized_particles ? radius * radius_ratios[slot] : radius;
    return vec4(position, splat_radius);
}

// Spheres take their NDC bounds from sphere_bounds.glsl's intervals.
bool particle_ndc_bounds(vec3 view_centre, vec2 focal, out vec4 box)
{
    box = vec4(0.0);
    return false;
}
