#version 450 core
// Which pixels the composite shades as fluid, and the depths written for
// them and for the floor: linked into the background program
// (background.frag.glsl: the floor's depth, and the mask where it lays it
// down) and the two composite programs (composite_pass.c), which must agree
// on all of it.

vec3 view_ray(vec2 window);

layout(binding = 0) uniform sampler2D surface_depth;   // smoothed linear depth, 0 = no fluid

layout(location = 16) uniform vec4 floor_plane;        // view space, dot(xyz, x) + w > 0 above; (0,0,0,1) = none
layout(location = 17) uniform vec2 depth_projection;   // P[2][2], P[3][2]
layout(location = 54) uniform vec2 depth_texel_uv;     // 1 / surface_depth's texture size

// Stands for "no floor on this ray": beyond any far plane, still finite.
const float beyond_everything = 3.0e38;

// Linear depth at which this pixel's ray meets the floor.
float floor_depth(vec3 ray)
{
    float rate = dot(floor_plane.xyz, ray);
    float t = rate < 0.0 ? -floor_plane.w / rate : -1.0;
    return t > 0.0 ? t : beyond_everything;
}

float window_depth(float z)
{
    float ndc = depth_projection.y / z - depth_projection.x;
    return clamp(0.5 * ndc + 0.5, 0.0, 1.0);
}

// Whether this fragment's pixel shows fluid in front of the floor; z is the
// fluid's depth and z_floor the floor's either way.
bool fluid_here(out float z, out float z_floor)
{
    // The passes sample the depth through a nearest sampler (gl_util.h), so
    // the lookup at the pixel's centre returns its texel unchanged, in fewer
    // instructions than texelFetch on llvmpipe (bench/RESULTS.md).
    z = textureLod(surface_depth, gl_FragCoord.xy * depth_texel_uv, 0.0).r;
    z_floor = floor_depth(view_ray(gl_FragCoord.xy));
    return z > 0.0 && z < z_floor;
}
