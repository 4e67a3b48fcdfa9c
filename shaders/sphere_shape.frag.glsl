#version 450 core
// The particle as a sphere, fragment side: the shape the splats' fragment
// shaders cast and shade (ellipsoid_shape.frag.glsl is the anisotropic one),
// at the radius the vertex side chose for it (sphere_shape.vert.glsl).

bool cast_sphere_ray(vec2 pixel, vec3 centre, float radius, out float depth, out float chord);

layout(location = 6) flat in float splat_radius;   // this particle's radius, world units

bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord)
{
    return cast_sphere_ray(pixel, centre, splat_radius, depth, chord);
}

// The outward unit normal at `hit` on the sphere (view space).
vec3 particle_normal(vec3 hit, vec3 centre)
{
    return (hit - centre) / splat_radius;
}
