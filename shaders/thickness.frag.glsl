#version 450 core
// Thickness (van der Laan et al. 2009, §3.3, eq. 9): each sphere adds the
// length of the view ray inside it, so the additive sum is fluid thickness in
// world units.

bool cast_sphere_ray(vec3 centre, out float depth, out float chord);

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 0) out float thickness;

void main()
{
    float depth, chord;
    if (!cast_sphere_ray(sphere_centre, depth, chord))
        discard;
    thickness = chord;
}
