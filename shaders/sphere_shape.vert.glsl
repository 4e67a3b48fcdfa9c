#version 450 core
// The particle as a sphere of the uniform radius at its position: the vertex
// side of a sphere sprite (sphere.vert.glsl).

layout(location = 3) uniform float radius;   // world units

vec4 particle_bounds(int slot, vec3 position)
{
    return vec4(position, radius);
}

// Spheres take their NDC bounds from sphere_bounds.glsl's intervals.
bool particle_ndc_bounds(vec3 view_centre, vec2 focal, out vec4 box)
{
    box = vec4(0.0);
    return false;
}
