#version 450 core
// Foam: the surface particles where the flow traps air (foam_classes.h,
// Ihmsen et al. 2012), each a soft disc of diffuse white facing the camera
// over the composited surface (foam_pass.h). A disc is its own size (a
// fraction of the sprite, from its particle's id) and opacity (from how far
// its trapped-air potential passed the frame's threshold); its coverage falls
// smoothly to 0 at its rim, so overlapping discs make a white patch with a
// soft edge and a lone one a faint fleck, never a hard bead. Lit as a rough
// white hemisphere: the sky all round, the sun on the side facing it.

layout(location = 1) uniform vec4 projection;       // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;
layout(location = 10) uniform vec3 light_view;      // unit, towards the light, view space

// Per foam particle, in draw order (foam_pass.c): x its disc's radius per
// sprite radius, y its opacity at the centre.
layout(std430, binding = 18) readonly buffer foam_looks {
    vec4 looks[];
};
layout(location = 0) flat in vec3 sphere_centre;    // view space
layout(location = 1) flat in int particle_slot;
layout(location = 6) flat in float splat_radius;    // the sprite's radius, world units

layout(location = 0) out vec4 color;

const vec3 albedo = vec3(0.92, 0.94, 0.96);   // foam: white, a trace of the sky's blue
const float sky_light = 0.68;                 // what the sky alone lights
const float sun_light = 0.32;                 // what the sun adds facing it

void main()
{
    vec4 look = looks[particle_slot];
    vec3 dir = vec3((gl_FragCoord.xy / viewport * 2.0 - 1.0) / projection.xy, -1.0);
    // Where the pixel's ray crosses the plane of the disc's centre, in disc radii.
    vec2 p = (dir * -sphere_centre.z - sphere_centre).xy / (splat_radius * look.x);
    float r2 = dot(p, p);
    if (r2 >= 1.0)
        discard;
    // Foam is rough: lit as a whole, not shaded as a ball, so no disc stands
    // out of the patch it merges into. The sun lights it as much as it lights
    // the surface facing the camera.
    vec3 lit = albedo * (sky_light + sun_light * max(light_view.z, 0.0));
    // Gaussian-like, to nothing at the rim: discs sum into a smooth patch.
    float coverage = (1.0 - r2) * (1.0 - r2);
    color = vec4(lit, look.y * coverage);
}
