#version 450 core
// Depth and thickness of the spheres in one splat. Attachment 0 gets the
// linear view depth of the sphere's front (van der Laan et al. 2009, §3.1),
// blended with GL_MIN so the nearest sphere wins without a depth buffer;
// attachment 1 the sphere's thickness (§3.3, thickness_chord.glsl),
// blended additively. One rasterisation of the spheres serves both images
// (on a software rasterizer it is a pass's largest cost), and without
// gl_FragDepth nothing waits on a depth test. Background stays at the clear
// value +inf in attachment 0 until depth_resolve.frag.glsl turns it into 0.

// The particle's shape, sphere or ellipsoid: sphere_shape.frag.glsl, ellipsoid_shape.frag.glsl.
bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord);
float thickness_above_floor(vec2 pixel, float depth, float chord);

layout(location = 1) uniform vec4 projection;   // P[0][0], P[1][1], P[2][2], P[3][2]

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 0) out float linear_depth;
layout(location = 1) out float thickness;

void main()
{
    float depth, chord;
    if (!cast_particle_ray(gl_FragCoord.xy, sphere_centre, depth, chord))
        discard;
    float ndc_z = (projection.w - projection.z * depth) / depth;
    // In front of the near plane no depth is seen (+inf leaves the minimum
    // alone), but the fluid there still has thickness.
    linear_depth = ndc_z < -1.0 ? uintBitsToFloat(0x7f800000u) : depth;
    thickness = thickness_above_floor(gl_FragCoord.xy, depth, chord);
}
