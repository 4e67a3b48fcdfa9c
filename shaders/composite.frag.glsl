#version 450 core
// Compositing (van der Laan et al. 2009, §3.5, eqs. 13-15): normals from the
// smoothed depth, Fresnel between refraction and reflection, Phong specular.

vec3 view_ray(vec2 window);
vec3 to_world_point(vec3 view_point);
vec3 to_world_direction(vec3 view_direction);
vec3 scene_radiance(vec3 origin, vec3 dir);

layout(binding = 0) uniform sampler2D surface_depth;   // smoothed linear depth, 0 = no fluid
layout(binding = 1) uniform sampler2D thickness;       // world units
layout(binding = 2) uniform sampler2D background;      // the scene without fluid, linear RGB

layout(location = 0) uniform vec2 focal;               // P[0][0], P[1][1]
layout(location = 5) uniform vec2 viewport;
layout(location = 6) uniform vec3 light_view;          // unit, towards the light, view space
layout(location = 7) uniform vec3 fluid_color;         // linear RGB seen through thick fluid
layout(location = 8) uniform vec3 absorption;          // per world unit of thickness
layout(location = 9) uniform float fresnel_f0;
layout(location = 10) uniform float refraction_strength;  // γ of eq. 15: world offset per unit thickness
layout(location = 11) uniform float edge_thickness;       // world units; thinner fluid fades out

const float specular_strength = 0.5;
const float shininess = 150.0;
// Refraction may shift the background by at most this fraction of the image,
// so very thick fluid cannot sample far-away, unrelated parts of the scene.
const float max_shift_fraction = 0.05;

layout(location = 0) out vec4 color;

float depth_at(ivec2 p)
{
    ivec2 size = textureSize(surface_depth, 0);
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size)))
        return 0.0;
    return texelFetch(surface_depth, p, 0).r;
}

vec3 view_point(ivec2 p, float z)
{
    return view_ray(vec2(p) + 0.5) * z;
}

// Tangent along `axis` from the one-sided difference with the smaller depth
// step: across a silhouette the other side is another surface or background,
// and a central difference would bend the normal there (§3.5).
vec3 surface_tangent(ivec2 p, ivec2 axis, vec3 centre, float z)
{
    float z_fwd = depth_at(p + axis);
    float z_bwd = depth_at(p - axis);
    bool fwd = z_fwd > 0.0;
    bool bwd = z_bwd > 0.0;
    if (fwd && bwd) {
        fwd = abs(z_fwd - z) <= abs(z - z_bwd);
        bwd = !fwd;
    }
    if (fwd)
        return view_point(p + axis, z_fwd) - centre;
    if (bwd)
        return centre - view_point(p - axis, z_bwd);
    return vec3(0.0);
}

vec3 surface_normal(ivec2 p, vec3 centre, float z)
{
    vec3 n = cross(surface_tangent(p, ivec2(1, 0), centre, z), surface_tangent(p, ivec2(0, 1), centre, z));
    float len = length(n);
    if (len == 0.0)
        return vec3(0.0, 0.0, 1.0);   // an isolated pixel: assume it faces the camera
    n /= len;
    return dot(n, centre) > 0.0 ? -n : n;   // towards the camera at the origin
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = depth_at(p);
    if (z <= 0.0) {
        color = vec4(texelFetch(background, p, 0).rgb, 1.0);
        return;
    }
    vec3 centre = view_point(p, z);
    vec3 n = surface_normal(p, centre, z);
    vec3 v = normalize(-centre);
    float t = texelFetch(thickness, p, 0).r;

    float cos_view = clamp(dot(n, v), 0.0, 1.0);
    float fresnel = fresnel_f0 + (1.0 - fresnel_f0) * pow(1.0 - cos_view, 5.0);

    // Eqs. 14-15: background seen through the fluid, shifted by β·n with
    // β = γ·T (world units, projected to pixels at this depth), and
    // attenuated per channel by Beer-Lambert towards the fluid colour.
    vec2 shift = refraction_strength * t * n.xy * 0.5 * viewport * focal / z;
    vec2 max_shift = max_shift_fraction * viewport;
    shift = clamp(shift, -max_shift, max_shift);
    vec3 behind = texture(background, (gl_FragCoord.xy + shift) / viewport).rgb;
    vec3 refracted = mix(fluid_color, behind, exp(-absorption * t));

    vec3 reflected = scene_radiance(to_world_point(centre), to_world_direction(reflect(-v, n)));

    vec3 half_vector = normalize(v + light_view);
    float specular = specular_strength * pow(max(dot(n, half_vector), 0.0), shininess);

    vec3 fluid = mix(refracted, reflected, fresnel) + vec3(specular);
    // Silhouettes are the rims of single sprites, jagged and seen at grazing
    // angles; fading out where the fluid is thinner than a particle (the
    // thickness falls smoothly to 0 there) softens them (cf. the silhouette
    // map of Instant Liquids).
    float coverage = smoothstep(0.0, edge_thickness, t);
    color = vec4(mix(texelFetch(background, p, 0).rgb, fluid, coverage), 1.0);
}
