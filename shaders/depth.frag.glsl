#version 450 core
// Sphere depth (van der Laan et al. 2009, §3.1): linear view depth of the
// sphere's front surface into the colour target, the matching window depth
// into the depth buffer so the nearest sphere wins.

bool cast_sphere_ray(vec3 centre, out float depth, out float chord);

layout(location = 1) uniform vec4 projection;   // P[0][0], P[1][1], P[2][2], P[3][2]

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 0) out float linear_depth;
layout(depth_greater) out float gl_FragDepth;

void main()
{
    float depth, chord;
    if (!cast_sphere_ray(sphere_centre, depth, chord))
        discard;
    float ndc_z = (projection.w - projection.z * depth) / depth;
    if (ndc_z < -1.0)
        discard;   // in front of the near plane
    linear_depth = depth;
    gl_FragDepth = 0.5 * ndc_z + 0.5;
}
