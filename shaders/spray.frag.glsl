#version 450 core
// Spray: the isolated particles (spray_classes.h, or below the density
// threshold), drawn as small clear droplets over the composited fluid, each
// of its own size (a hash of its id, so the same droplet keeps its size from
// frame to frame and no two runs differ). A droplet is a tiny lens: through
// its body it shows the world upside down (the bright sky in its lower half,
// the darker ground in its upper half), its rim reflects the sky (Fresnel,
// Schlick, IOR 1.33) and it catches the sun as one sharp highlight; so it
// reads as water, not as a white bead. Speed whitens it towards foam when
// `whitening` (settings.foam) asks for it (Cords & Staadt, Instant Liquids,
// §4: the velocity map shifts the colour to white).
// With velocities (streak_room > 1) a droplet is a streak along its velocity
// across the view (spray_pass.h): an ellipse as long as 1 + (room - 1) x its
// speed across the view over (its speed + the frame's mean speed), in a
// sprite `streak_room` times the droplet's; its body is spread over the
// longer streak, so it grows fainter as it grows longer.

// The particle's shape, sphere or ellipsoid: sphere_shape.frag.glsl, ellipsoid_shape.frag.glsl.
bool cast_particle_ray(vec2 pixel, vec3 centre, out float depth, out float chord);
vec3 particle_normal(vec3 hit, vec3 centre);
float particle_speed();
uint particle_id();

layout(location = 1) uniform vec4 projection;        // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;
layout(location = 10) uniform vec3 light_view;       // unit, towards the light, view space
layout(location = 11) uniform vec3 fluid_color;      // linear RGB
layout(location = 12) uniform float whitening;       // settings.foam: how white fast spray gets
layout(location = 13) uniform float speed_reference; // a droplet this fast is half-way to white
layout(location = 0) uniform mat4 view_matrix;       // world -> view
layout(location = 14) uniform int first_spray;       // draw slot of the first droplet: velocities[0]
layout(location = 15) uniform float mean_speed;      // the frame's mean speed
layout(location = 16) uniform float streak_room;     // the sprite's radius per round droplet's; 1: no velocities

// World velocity per droplet, from draw slot first_spray on (spray_pass.c).
layout(std430, binding = 17) readonly buffer spray_velocities {
    vec4 velocities[];
};
layout(location = 1) flat in int particle_slot;
layout(location = 6) flat in float splat_radius;     // the sprite's radius, world units

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 0) out vec4 color;

// Droplets span this fraction of the sprite's radius and more, up to all of it.
const float smallest = 0.45;
const float tint = 0.1;          // how much of the fluid's colour a droplet this small holds
const float body_opacity = 0.55; // what shows through a droplet's body is mostly the image it inverts
const vec3 sky = vec3(0.80, 0.88, 1.0);
const vec3 ground = vec3(0.32, 0.30, 0.28);
const float schlick_r0 = 0.02;   // ((1.33 - 1) / (1.33 + 1))^2

// A droplet's size from its id: an integer hash (Wang), uniform in [smallest, 1).
float droplet_size(uint id)
{
    id = (id ^ 61u) ^ (id >> 16);
    id *= 9u;
    id ^= id >> 4;
    id *= 0x27d4eb2du;
    id ^= id >> 15;
    return smallest + (1.0 - smallest) * float(id >> 8) / 16777216.0;
}

void main()
{
    float depth, chord;
    if (!cast_particle_ray(gl_FragCoord.xy, sphere_centre, depth, chord))
        discard;
    vec3 dir = vec3((gl_FragCoord.xy / viewport * 2.0 - 1.0) / projection.xy, -1.0);
    // The droplet: a sphere of its own size inside the particle's, centred
    // on it, stretched along its velocity across the view.
    vec2 along = vec2(1.0, 0.0);
    float stretch = 1.0;
    if (streak_room > 1.0) {
        vec3 v = mat3(view_matrix) * velocities[particle_slot - first_spray].xyz;
        float across_view = length(v.xy);
        if (across_view > 0.0) {
            along = v.xy / across_view;
            stretch = 1.0 + (streak_room - 1.0) * across_view / (length(v) + mean_speed);
        }
    }
    // Where the pixel's ray crosses the plane of the droplet's centre, in
    // round droplets' radii: the droplet's own outline, whatever the sprite.
    vec2 p = (dir * -sphere_centre.z - sphere_centre).xy / splat_radius * streak_room / droplet_size(particle_id());
    vec2 q = vec2(dot(p, along) / stretch, dot(p, vec2(-along.y, along.x)));
    float q2 = dot(q, q);
    if (q2 >= 1.0)
        discard;
    vec3 n = vec3(q.x * along + q.y * vec2(-along.y, along.x), sqrt(1.0 - q2));
    float fresnel = schlick_r0 + (1.0 - schlick_r0) * pow(1.0 - n.z, 5.0);
    vec3 inverted = mix(sky, ground, 0.5 + 0.5 * n.y);
    vec3 body = mix(inverted, inverted * fluid_color / max(max(fluid_color.r, fluid_color.g), fluid_color.b), tint);
    vec3 reflected = mix(sky, ground, 0.5 - 0.5 * reflect(vec3(0.0, 0.0, -1.0), n).y);
    float highlight = pow(max(dot(reflect(-light_view, n), vec3(0.0, 0.0, 1.0)), 0.0), 80.0);
    vec3 water = mix(body, reflected, fresnel) + vec3(highlight);
    float alpha = clamp(mix(body_opacity, 1.0, fresnel) + highlight, 0.0, 1.0) / sqrt(stretch);
    float speed = particle_speed();
    float white = clamp(whitening * speed / (speed + speed_reference), 0.0, 1.0);
    // Fading towards the rim keeps tiny droplets from aliasing.
    float edge = clamp(4.0 * n.z, 0.0, 1.0);
    color = vec4(mix(water, vec3(1.0), white), mix(alpha, 1.0, white) * edge);
}
