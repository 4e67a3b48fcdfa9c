#version 450 core
// Surface noise (van der Laan et al. 2009, §3.4, eqs. 10-11): every surface
// particle splats one octave of gradient noise, weighted by a kernel over its
// sprite and by exp(-(depth below the smoothed surface)²); additive blending
// sums the splats into N(x, y). The pattern is chosen by the particle's id and
// laid out in the particle's own coordinates, so it moves with the particle.
// The patent's 3D noise texture (two axes across the sprite, one by id) is
// computed here instead of looked up: a hash of (lattice cell, id) gives the
// lattice gradients.

bool cast_sphere_ray(vec2 pixel, vec3 centre, float radius, out float depth, out float chord);
uint particle_id();
float particle_amplitude();

layout(binding = 0) uniform sampler2D surface_depth;   // smoothed linear depth, 0 = no fluid

layout(location = 1) uniform vec4 projection;          // P[0][0], P[1][1], P[2][2], P[3][2]
layout(location = 2) uniform vec2 viewport;
layout(location = 10) uniform float noise_amplitude;   // settings.noise

layout(location = 0) flat in vec3 sphere_centre;
layout(location = 6) flat in float splat_radius;       // this particle's radius (sphere_shape.vert.glsl)
layout(location = 0) out float noise;

// Lattice cells per particle radius: features about the particle's size,
// below what the simulation resolves yet large enough not to alias.
const float cells_per_radius = 0.5;
// 2D gradient noise spans about ±0.7; this brings it to about ±1.
const float noise_scale = 1.4;

uint hash(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

vec2 lattice_gradient(ivec2 cell, uint seed)
{
    uint h = hash(uint(cell.x) ^ hash(uint(cell.y) ^ seed));
    float angle = float(h) * (6.28318530718 / 4294967296.0);
    return vec2(cos(angle), sin(angle));
}

// Perlin's gradient noise with the quintic fade, so its gradient (which
// perturbs the normals) is continuous too.
float gradient_noise(vec2 p, uint seed)
{
    ivec2 cell = ivec2(floor(p));
    vec2 f = fract(p);
    vec2 fade = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    float n00 = dot(lattice_gradient(cell, seed), f);
    float n10 = dot(lattice_gradient(cell + ivec2(1, 0), seed), f - vec2(1.0, 0.0));
    float n01 = dot(lattice_gradient(cell + ivec2(0, 1), seed), f - vec2(0.0, 1.0));
    float n11 = dot(lattice_gradient(cell + ivec2(1, 1), seed), f - vec2(1.0, 1.0));
    return mix(mix(n00, n10, fade.x), mix(n01, n11, fade.x), fade.y);
}

void main()
{
    float depth, chord;
    if (!cast_sphere_ray(gl_FragCoord.xy, sphere_centre, splat_radius, depth, chord))
        discard;
    float surface = texelFetch(surface_depth, ivec2(gl_FragCoord.xy), 0).r;
    if (surface <= 0.0)
        discard;
    vec3 dir = vec3((gl_FragCoord.xy / viewport * 2.0 - 1.0) / projection.xy, -1.0);
    // Where this pixel meets the sphere, in radii from its centre: (x, y) of
    // eq. 10, inside the unit disc.
    vec2 local = (depth * dir - sphere_centre).xy / splat_radius;
    // (1 - ρ²)³ is the Gaussian e^(-3ρ²) near the centre but reaches 0 with
    // zero slope at the rim: no sprite outline shows in N or its gradient.
    float rim = max(1.0 - dot(local, local), 0.0);
    float kernel = rim * rim * rim;
    float below = max(depth - surface, 0.0) / splat_radius;
    uint id = particle_id();
    // The id also shifts the lattice, so no two particles share cell borders.
    vec2 offset = vec2(hash(id) & 0xffu, hash(id + 1u) & 0xffu) / 256.0;
    float n = noise_scale * gradient_noise(local * cells_per_radius + offset, hash(id + 2u));
    noise = noise_amplitude * particle_amplitude() * n * kernel * exp(-below * below);
}
