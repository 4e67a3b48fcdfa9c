#version 450 core
// Thickness (van der Laan et al. 2009, §3.3, eq. 9): each sphere adds the
// length of the view ray inside it above the floor (thickness_chord.glsl),
// so the additive sum is fluid thickness in world units. Used where thickness
// is splatted on its own, at reduced resolution; at full resolution
// surface_splat.frag.glsl writes it with the depth.

// The particle's shape, sphere or ellipsoid: sphere_shape.frag.glsl, ellipsoid_shape.frag.glsl.
bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord);
float thickness_above_floor(vec2 pixel, float depth, float chord);

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 0) out float thickness;

void main()
{
    float depth, chord;
    if (!cast_particle_ray(gl_FragCoord.xy, sphere_centre, depth, chord))
        discard;
    thickness = thickness_above_floor(gl_FragCoord.xy, depth, chord);
}
