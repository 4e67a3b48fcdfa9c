#version 450 core
// The particle as a sphere, fragment side: the shape the splats' fragment
// shaders cast and shade (ellipsoid_shape.frag.glsl is the anisotropic one).

bool cast_sphere_ray(vec2 pixel, vec3 centre, out float depth, out float chord);

layout(location = 3) uniform float radius;

bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord)
{
    return cast_sphere_ray(pixel, centre, depth, chord);
}

// The outward unit normal at `hit` on the sphere (view space).
vec3 particle_normal(vec3 hit, vec3 centre)
{
    return (hit - centre) / radius;
}
