#version 450 core
// Spray: the particles below the density threshold, drawn as small shaded
// droplets over the composited fluid and whitened by their speed (Cords &
// Staadt, Instant Liquids, §4: the velocity map shifts the colour to white).

// The particle's shape, sphere or ellipsoid: sphere_shape.frag.glsl, ellipsoid_shape.frag.glsl.
bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord);
vec3 particle_normal(vec3 hit, vec3 centre);
float particle_speed();

layout(location = 1) uniform vec4 projection;        // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;
layout(location = 10) uniform vec3 light_view;       // unit, towards the light, view space
layout(location = 11) uniform vec3 fluid_color;      // linear RGB
layout(location = 12) uniform float whitening;       // settings.foam: how white fast spray gets
layout(location = 13) uniform float speed_reference; // a droplet this fast is half-way to white

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 0) out vec4 color;

// Droplets are mostly white, as sunlit spray is: the fluid's tint only
// shows faintly in them, and their shaded side stays bright.
const float tint = 0.15;
const float opacity = 0.85;

void main()
{
    float depth, chord;
    if (!cast_particle_ray(gl_FragCoord.xy, sphere_centre, depth, chord))
        discard;
    vec3 dir = vec3((gl_FragCoord.xy / viewport * 2.0 - 1.0) / projection.xy, -1.0);
    vec3 n = particle_normal(depth * dir, sphere_centre);
    float speed = particle_speed();
    float white = clamp(whitening * speed / (speed + speed_reference), 0.0, 1.0);
    vec3 albedo = mix(mix(vec3(1.0), fluid_color, tint), vec3(1.0), white);
    float light = 0.8 + 0.3 * max(dot(n, light_view), 0.0);
    // Fading towards the rim (n.z -> 0) keeps tiny droplets from aliasing.
    color = vec4(albedo * light, opacity * clamp(2.0 * n.z, 0.0, 1.0));
}
