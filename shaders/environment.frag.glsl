#version 450 core
// The scene around the fluid as a function of world-space rays: a sky with a
// horizon, clouds, a sun and the ground below it, over a checkered floor lit by that
// sun and sky (sky alone when a client background replaces the floor). The
// background (what refraction sees) and the reflections both come from
// scene_radiance, so one light and one sky shape the whole image: a surface
// tilted towards the camera reflects the ground, one tilted away the bright
// horizon and the sky, and the highlight sits where the sun is reflected.
// Radiance is linear HDR RGB (the sun disc is far brighter than 1);
// display_color() turns it into the image's colour (exposure, filmic curve).

layout(location = 20) uniform vec3 world_up;         // unit
layout(location = 21) uniform vec3 sun_direction;    // unit, towards the sun
layout(location = 22) uniform vec3 floor_axis_u;     // unit, in the floor plane
layout(location = 23) uniform vec3 floor_axis_v;     // unit, in the floor plane, normal to u
layout(location = 24) uniform float floor_height;    // the floor is dot(x, world_up) = floor_height
layout(location = 25) uniform float checker_size;    // world units
layout(location = 26) uniform float pixel_angle;     // radians one pixel spans at the image centre
#ifdef FC_VARIANT
// A shader variant (shader_variants.h): the features are constants, and the
// compiler removes the code of those that are off, which a software
// rasterizer would otherwise run for every pixel and discard.
const bool has_floor = FC_HAS_FLOOR != 0;
const bool has_shadow = FC_HAS_SHADOW != 0;
const bool has_mesh_shadow = FC_HAS_MESH_SHADOW != 0;
const bool floor_only = FC_FLOOR_ONLY != 0;   // every pixel of the draw sees the floor (background_regions.h)
#else
layout(location = 27) uniform bool has_floor;        // false: sky all around (a client background replaces the floor)
layout(location = 36) uniform bool has_shadow;
layout(location = 39) uniform bool has_mesh_shadow;
const bool floor_only = false;
#endif
layout(location = 28) uniform float exposure_scale;  // 2^exposure
layout(location = 29) uniform bool tone_map;         // true: 8-bit output, false: linear HDR (float output)
layout(location = 32) uniform mat4 sun_shadow;        // world point -> shadow map, (u w, v w, 0, w), uv in [0,1]
layout(location = 37) uniform vec3 shadow_extinction;  // per world unit of the fluid's thickness seen from the sun
layout(location = 38) uniform vec2 shadow_uv_scale;    // the map's share of its texture
layout(location = 40) uniform vec2 shadow_uv_last;     // its last texel centres, uv

layout(binding = 5) uniform sampler2D shadow_thickness; // the fluid's thickness along sun rays, world units
// Meshes (mesh_pass.c): seen from the sun through the same transform, the
// nearest opaque mesh's and the nearest fluid's distance from the sun.
layout(location = 48) uniform vec4 sun_depth_uv_scale;   // xy: the fluid's depth map's share, zw: the meshes'
layout(location = 49) uniform float mesh_shadow_bias;    // world units a surface may lie behind its own depth
layout(binding = 6) uniform sampler2D fluid_sun_depth;   // linear depth from the sun, 0 = no fluid
layout(binding = 7) uniform sampler2D mesh_sun_depth;    // linear depth from the sun, +inf = no mesh

const vec3 zenith_color = vec3(0.16, 0.34, 0.78);
const vec3 horizon_color = vec3(1.05, 1.08, 1.10);
const vec3 ground_near_horizon = vec3(0.36, 0.33, 0.29);
const vec3 ground_color = vec3(0.16, 0.14, 0.12);
const vec3 sun_color = vec3(1.00, 0.93, 0.82);
const float sun_disc_radiance = 60.0;
const float sun_disc_cos = 0.99985;                  // about 1 degree across
const float sun_irradiance = 1.4;                    // on a surface facing the sun
// A mid-grey floor with contrast: water refracting it and white spray over
// it both show, where a near-white floor washed them out.
const vec3 checker_light = vec3(0.62, 0.60, 0.56);
const vec3 checker_dark = vec3(0.20, 0.21, 0.23);
// Haze only far away: near the fluid the floor keeps its contrast.
const float fog_distance_in_checkers = 200.0;
const vec3 cloud_color = vec3(1.25, 1.25, 1.28);
const vec3 cloud_shade = vec3(0.62, 0.66, 0.74);

// Value noise on a lattice, hashed without tables (Dave Hoskins' hash).
float lattice_value(vec2 cell)
{
    vec3 h = fract(vec3(cell.xyx) * 0.1031);
    h += dot(h, h.yzx + 33.33);
    return fract((h.x + h.y) * h.z);
}

float value_noise(vec2 x)
{
    vec2 cell = floor(x), f = fract(x);
    vec2 w = f * f * (3.0 - 2.0 * f);
    return mix(mix(lattice_value(cell), lattice_value(cell + vec2(1, 0)), w.x),
               mix(lattice_value(cell + vec2(0, 1)), lattice_value(cell + vec2(1, 1)), w.x), w.y);
}

// Cumulus over a plane above the scene: four octaves of value noise where
// the ray meets the plane, thresholded into separate clouds, denser towards
// their middles. A fixed pattern (no randomness between renders); clouds
// give the sky the structure that reflections on water show along waves.
// Returns (coverage, thickness) in [0, 1].
vec2 clouds(vec3 dir, float elevation)
{
    vec2 across = vec2(dot(dir, floor_axis_u), dot(dir, floor_axis_v)) / (elevation + 0.08);
    vec2 x = 1.3 * across + vec2(17.0, 3.0);
    float sum = 0.0, amplitude = 0.5;
    for (int octave = 0; octave < 4; octave++) {
        sum += amplitude * value_noise(x);
        x = mat2(1.6, 1.2, -1.2, 1.6) * x;
        amplitude *= 0.5;
    }
    float coverage = smoothstep(0.48, 0.62, sum) * smoothstep(0.0, 0.12, elevation);
    return vec2(coverage, smoothstep(0.55, 0.85, sum));
}

// Sky above the horizon, ground below it, the horizon itself a sharp bright
// line: in reflections it draws the surface's shape as a contour.
vec3 sky_radiance(vec3 dir)
{
    float elevation = dot(dir, world_up);
    vec3 sky;
    if (elevation >= 0.0) {
        sky = mix(horizon_color, zenith_color, pow(elevation, 0.45));
        vec2 cloud = clouds(dir, elevation);
        sky = mix(sky, mix(cloud_color, cloud_shade, cloud.y), cloud.x);
    } else
        sky = mix(ground_near_horizon, ground_color, pow(min(-elevation * 4.0, 1.0), 0.6));
    float sun = max(dot(dir, sun_direction), 0.0);
    vec3 glow = sun_color * (0.35 * pow(sun, 12.0) + 1.5 * pow(sun, 300.0));
    float disc = smoothstep(sun_disc_cos - 0.00005, sun_disc_cos, sun);
    return sky + glow + sun_color * sun_disc_radiance * disc;
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

// The share of sunlight the opaque meshes let reach `s` (a point through
// sun_shadow): 4 taps of a depth comparison, softening the edge a little.
float mesh_sun_visibility(vec4 s)
{
    if (!has_mesh_shadow)
        return 1.0;
    vec2 uv = s.xy / s.w;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return 1.0;
    vec2 texel = 1.0 / vec2(textureSize(mesh_sun_depth, 0));
    float lit = 0.0;
    for (int i = 0; i < 4; i++) {
        vec2 corner = vec2(i & 1, i >> 1) - 0.5;
        float nearest = texture(mesh_sun_depth, (uv + texel * corner) * sun_depth_uv_scale.zw).r;
        lit += s.w <= nearest + mesh_shadow_bias ? 1.0 : 0.0;
    }
    return lit / 4.0;
}

// Whether the point `s` (through sun_shadow) lies sunward of all the fluid
// on its sun ray: then the fluid's thickness there is behind it, no shadow.
bool in_front_of_fluid(vec4 s)
{
    vec2 uv = s.xy / s.w;
    float fluid = texture(fluid_sun_depth, clamp(uv, 0.0, 1.0) * sun_depth_uv_scale.xy).r;
    return fluid <= 0.0 || s.w < fluid;
}

// Light reaching a floor point from the sun through the fluid (Beer-Lambert
// on the thickness the fluid has along the sun ray), per channel; 1 outside
// the shadow map. The map holds a box of 4x4 texels already (shadow_box.frag.glsl),
// softening the edge like a sun of finite size would.
vec3 sun_transmission_of(vec3 hit, bool may_be_in_front)
{
    if (!has_shadow)
        return vec3(1.0);
    vec4 s = sun_shadow * vec4(hit, 1.0);
    vec2 uv = s.xy / s.w;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return vec3(1.0);
    float meshes = mesh_sun_visibility(s);
    if (may_be_in_front && in_front_of_fluid(s))
        return vec3(meshes);
    float t = texture(shadow_thickness, min(uv * shadow_uv_scale, shadow_uv_last)).r;
    return meshes * exp(-shadow_extinction * t);
}

// The floor lies below all the fluid.
vec3 sun_transmission(vec3 hit)
{
    return sun_transmission_of(hit, false);
}

// `distance` along the ray and the cosine between ray and floor normal give
// the pixel's footprint on the floor without screen-space derivatives, which
// reflections and silhouettes would make undefined.
vec3 floor_radiance(vec3 hit, float distance, float cos_incidence)
{
    vec2 uv = vec2(dot(hit, floor_axis_u), dot(hit, floor_axis_v)) / checker_size;
    float footprint = distance * pixel_angle / (checker_size * max(cos_incidence, 0.02));
    vec3 albedo = mix(checker_dark, checker_light, filtered_checker(uv, footprint));
    vec3 sky_light = 0.25 * (horizon_color + zenith_color);
    vec3 sun_light = sun_irradiance * sun_color * max(dot(world_up, sun_direction), 0.0) * sun_transmission(hit);
    float fog = 1.0 - exp(-distance / (fog_distance_in_checkers * checker_size));
    return mix(albedo * (sky_light + sun_light), horizon_color, fog);
}

// A mesh's surface (mesh_shade.frag.glsl): diffuse under the sky and the
// sun, which the fluid and the opaque meshes may shadow, and a faint glint
// of the sun. Unit world vectors; view_direction points toward the eye.
vec3 surface_radiance(vec3 point, vec3 normal, vec3 albedo, vec3 view_direction)
{
    vec3 sky_light = 0.25 * (horizon_color + zenith_color) * (0.75 + 0.25 * dot(normal, world_up));
    float facing = max(dot(normal, sun_direction), 0.0);
    vec3 sun = sun_irradiance * sun_color * sun_transmission_of(point, true);
    float glint = pow(max(dot(normal, normalize(sun_direction + view_direction)), 0.0), 60.0);
    return albedo * (sky_light + sun * facing) + 0.15 * glint * sun;
}

vec3 scene_radiance(vec3 origin, vec3 dir)
{
    float height = dot(origin, world_up) - floor_height;
    float descent = -dot(dir, world_up);
    if (floor_only || (has_floor && height > 0.0 && descent > 0.0)) {
        float distance = height / descent;
        return floor_radiance(origin + distance * dir, distance, descent);
    }
    return sky_radiance(dir);
}

// The filmic curve of Narkowicz's ACES fit: a toe that keeps shadows, a
// shoulder that rolls highlights (the sun, its reflections) off to white
// instead of clipping them into flat patches.
vec3 filmic(vec3 x)
{
    return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// The radiance filmic() shows as y (y in [0, 1]): the root of its quadratic
// that is >= 0. A client's background image is a picture already, so it
// enters the scene through this and leaves the tone map unchanged.
vec3 inverse_filmic(vec3 y)
{
    y = clamp(y, 0.0, 0.999);
    vec3 a = 2.43 * y - 2.51;
    vec3 b = 0.59 * y - 0.03;
    vec3 c = 0.14 * y;
    return (-b - sqrt(max(b * b - 4.0 * a * c, 0.0))) / (2.0 * a);
}

vec3 display_color(vec3 radiance)
{
    vec3 exposed = radiance * exposure_scale;
    return tone_map ? filmic(exposed) : exposed;
}

// A client image's colour as scene radiance: what the filmic curve maps back
// to it, so that 8-bit output shows the picture unchanged where no fluid is.
vec3 picture_radiance(vec3 color)
{
    return inverse_filmic(color) / exposure_scale;
}
