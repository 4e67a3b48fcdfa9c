#version 450 core
// The scene around the fluid as a function of world-space rays: a procedural
// sky over a checkered floor (sky alone when a client background replaces the
// floor). The background (what refraction sees) and the reflections both come
// from scene_radiance, so a cube map or real geometry replaces the scene here
// alone. Radiance is linear RGB.

layout(location = 20) uniform vec3 world_up;         // unit
layout(location = 21) uniform vec3 sun_direction;    // unit, towards the sun
layout(location = 22) uniform vec3 floor_axis_u;     // unit, in the floor plane
layout(location = 23) uniform vec3 floor_axis_v;     // unit, in the floor plane, normal to u
layout(location = 24) uniform float floor_height;    // the floor is dot(x, world_up) = floor_height
layout(location = 25) uniform float checker_size;    // world units
layout(location = 26) uniform float pixel_angle;     // radians one pixel spans at the image centre
layout(location = 27) uniform bool has_floor;        // false: sky all around (a client background replaces the floor)

const vec3 horizon_color = vec3(0.80, 0.85, 0.90);
const vec3 zenith_color = vec3(0.15, 0.33, 0.70);
const vec3 ground_color = vec3(0.30, 0.28, 0.25);
const vec3 sun_color = vec3(1.00, 0.95, 0.85);
const vec3 checker_light = vec3(0.80, 0.78, 0.72);
const vec3 checker_dark = vec3(0.30, 0.32, 0.36);
const float fog_distance_in_checkers = 60.0;

vec3 sky_radiance(vec3 dir)
{
    float elevation = dot(dir, world_up);
    vec3 sky = elevation >= 0.0 ? mix(horizon_color, zenith_color, sqrt(elevation))
                                : mix(horizon_color, ground_color, sqrt(-elevation));
    float sun = max(dot(dir, sun_direction), 0.0);
    return sky + sun_color * (0.3 * pow(sun, 24.0) + 3.0 * pow(sun, 1200.0));
}

// Fraction of light squares in a box of `width` checker units around uv: the
// exact box-filtered pattern, so squares fade to their mean near the horizon
// instead of aliasing into moiré.
float filtered_checker(vec2 uv, float width)
{
    vec2 w = vec2(width + 1e-4);
    vec2 i = 2.0 * (abs(fract((uv - 0.5 * w) * 0.5) - 0.5) - abs(fract((uv + 0.5 * w) * 0.5) - 0.5)) / w;
    return 0.5 - 0.5 * i.x * i.y;
}

// `distance` along the ray and the cosine between ray and floor normal give
// the pixel's footprint on the floor without screen-space derivatives, which
// reflections and silhouettes would make undefined.
vec3 floor_radiance(vec3 hit, float distance, float cos_incidence)
{
    vec2 uv = vec2(dot(hit, floor_axis_u), dot(hit, floor_axis_v)) / checker_size;
    float footprint = distance * pixel_angle / (checker_size * max(cos_incidence, 0.02));
    vec3 albedo = mix(checker_dark, checker_light, filtered_checker(uv, footprint));
    vec3 irradiance = 0.55 * horizon_color + 0.6 * sun_color * max(dot(world_up, sun_direction), 0.0);
    float fog = 1.0 - exp(-distance / (fog_distance_in_checkers * checker_size));
    return mix(albedo * irradiance, horizon_color, fog);
}

vec3 scene_radiance(vec3 origin, vec3 dir)
{
    float height = dot(origin, world_up) - floor_height;
    float descent = -dot(dir, world_up);
    if (has_floor && height > 0.0 && descent > 0.0) {
        float distance = height / descent;
        return floor_radiance(origin + distance * dir, distance, descent);
    }
    return sky_radiance(dir);
}
