#version 450 core
// Compositing (van der Laan et al. 2009, §3.5, eqs. 13-15): Fresnel between
// the refracted background and the reflected environment, Phong specular,
// grey foam where the surface noise is strong. The last of two or three
// passes (composite_pass.c): it runs only where the mask set the stencil
// (fluid_mask.frag.glsl, or background.frag.glsl where the driver can export
// the stencil), over the colour and depth background.frag.glsl wrote.

layout(early_fragment_tests) in;

vec3 view_ray(vec2 window);
vec3 to_world_point(vec3 view_point);
vec3 to_world_direction(vec3 view_direction);
vec3 scene_radiance(vec3 origin, vec3 dir);
vec3 display_color(vec3 radiance);
struct surface_spans {
    ivec2 x;
    ivec2 y;
};

float depth_at(ivec2 p);
float noise_at(ivec2 p);
vec3 view_point(ivec2 p, float z);
surface_spans spans_at(ivec2 p, float z);
vec3 shading_normal(ivec2 p, vec3 centre, float z, surface_spans spans);
bool inside_surface(surface_spans spans);
bool fluid_here(out float z, out float z_floor);

layout(binding = 1) uniform sampler2D thickness;         // world units in r, any resolution (bilinear filtering);
                                                         // coloured: the colour times the thickness in gba
layout(binding = 2) uniform sampler2D background;        // the scene without fluid, linear RGB
layout(binding = 4) uniform samplerCube environment_map; // world directions, linear RGB

layout(location = 0) uniform vec2 focal;                 // P[0][0], P[1][1]
layout(location = 5) uniform vec2 viewport;
layout(location = 6) uniform vec3 light_view;            // unit, towards the light, view space
layout(location = 7) uniform vec3 fluid_color;           // linear RGB seen through thick fluid
layout(location = 8) uniform vec3 absorption;            // per world unit of thickness
layout(location = 9) uniform float fresnel_f0;
layout(location = 10) uniform float refraction;          // γ of eq. 15: pixels per pixel of projected thickness
layout(location = 11) uniform float specular_strength;   // k_s of eq. 13
layout(location = 12) uniform float particle_radius;     // world units
layout(location = 13) uniform float shininess;           // α of eq. 13
layout(location = 14) uniform float foam;                // settings.foam: how fast foam turns opaque
layout(location = 18) uniform vec2 foam_noise_range;     // mean |N| where foam starts and where it is complete
#ifdef FC_VARIANT
// A shader variant (shader_variants.h): features that are off are compiled out.
const bool use_environment_map = FC_USE_ENVIRONMENT_MAP != 0;
const bool colored = FC_COLORED != 0;
#define HAS_FOAM (FC_HAS_FOAM != 0)
#else
layout(location = 15) uniform bool use_environment_map;  // else the procedural scene is reflected
layout(location = 47) uniform bool colored;              // the fluid's colour is the thickness's (colour by attribute)
#define HAS_FOAM (foam > 0.0)
#endif
// Texture sizes, which may exceed the image in use (targets only grow): the
// background holds a viewport-sized image in its lower-left corner, the
// thickness one of thickness_size (half the viewport or less when blurred).
layout(location = 43) uniform vec2 thickness_texel_uv;         // 1 / the thickness texture's size
layout(location = 44) uniform vec2 background_texture_size;
layout(location = 45) uniform vec2 thickness_per_pixel;        // thickness texels per viewport pixel
layout(location = 46) uniform vec2 thickness_size;             // texels of the thickness image in use

// Refraction shifts the background by less than this fraction of the
// image's height, so that very thick fluid cannot sample far-away, unrelated
// parts of the scene, and approaches it smoothly (no clamp whose kink would
// show as a crease where the thickness or the slope grows).
const float max_shift_fraction = 0.02;
const vec3 foam_color = vec3(0.90, 0.92, 0.94);
// The sun's highlight at specular 1, linear HDR: bright enough that the
// filmic shoulder shows it near white, as the sun's glint on water is.
const vec3 highlight_radiance = 4.0 * vec3(1.00, 0.93, 0.82);

// Shape cues (issue 26): clear water shows a body's faces only by what it
// refracts and reflects, so its far and top faces and its foot fade into the
// scene. Two faint cues give them back: what shows through thick water dims a
// little (as through a thick body of real water, whose volume scatters light
// away), and a contact shadow darkens the water where it meets the floor.
// (A crease line where the depth bends sharply was tried and judged blind:
// it fired on single droplets as dark specks; bench/LOOK.md.)
layout(location = 57) uniform float contact_shadow;   // the most the water's foot darkens
layout(location = 58) uniform float depth_dimming;    // the most what shows through thick water dims
const float dimming_thickness = 12.0;       // particle radii at which 63% of the dimming is reached
const float contact_height = 2.5;           // particle radii of depth above the floor it fades over

layout(location = 0) out vec4 color;

vec3 reflected_radiance(vec3 origin, vec3 dir)
{
    return use_environment_map ? texture(environment_map, dir).rgb : scene_radiance(origin, dir);
}

// |N| around p, over about a particle's footprint: N changes sign from
// pixel to pixel, and foam is the patches where it is strong, not those
// pixels. The samples lie on a ring of one projected particle radius.
float noise_magnitude(ivec2 p, float z)
{
    float reach = clamp(particle_radius * 0.5 * viewport.y * focal.y / z, 1.0, 4.0);
    ivec2 size = ivec2(viewport);
    float sum = abs(noise_at(p));
    for (int i = 0; i < 8; i++) {
        float angle = 0.785398163 * float(i);
        ivec2 q = clamp(p + ivec2(round(reach * vec2(cos(angle), sin(angle)))), ivec2(0), size - 1);
        sum += abs(noise_at(q));
    }
    return sum / 9.0;
}

// The share of pixel p the fluid covers: 1 inside, and on the outline (a
// fluid pixel with a background neighbour) the share of its 3x3 block that
// is fluid, which is about the area an edge through the block leaves on the
// fluid's side. So the outline comes from the smoothed depth alone and is one
// anti-aliased pixel wide, whatever the thickness: thin fluid is clear
// (refraction and Fresnel show it), not faded into a halo.
float outline_coverage(ivec2 p)
{
    int fluid_pixels = 1;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            if (dx != 0 || dy != 0)
                fluid_pixels += depth_at(p + ivec2(dx, dy)) > 0.0 ? 1 : 0;
    return float(fluid_pixels) / 9.0;
}

vec3 shade_fluid(ivec2 p, float z, float z_floor, vec3 behind_here)
{
    vec3 centre = view_point(p, z);
    surface_spans spans = spans_at(p, z);
    vec3 n = shading_normal(p, centre, z, spans);
    vec3 v = normalize(-centre);
    // Bilinear upsampling, clamped to the last texel centres in use as for
    // the background below.
    vec2 thickness_texel = clamp(gl_FragCoord.xy * thickness_per_pixel, vec2(0.5), thickness_size - 0.5);
    vec4 thickness_sample = texture(thickness, thickness_texel * thickness_texel_uv);
    float t = thickness_sample.r;
    // Coloured by an attribute, the particles' colours splatted and blurred
    // with the thickness give the mean colour along the ray, which thick
    // fluid shows as it would show fluid_color (the way VTK's particle
    // colours absorb): it follows the surface.
    vec3 thick_color = colored ? thickness_sample.gba / max(t, 1e-30) : fluid_color;

    float cos_view = clamp(dot(n, v), 0.0, 1.0);
    float fresnel = fresnel_f0 + (1.0 - fresnel_f0) * pow(1.0 - cos_view, 5.0);

    // Eqs. 14-15: the background shifted by β·n with β = γ·T, T the
    // thickness as the pixels it spans at this depth: a slab displaces what is
    // behind it in proportion to its thickness (about (1 - 1/ior)·T), so a
    // droplet bends the floor as much at any image size or scene unit, and
    // attenuated per channel by Beer-Lambert towards the fluid colour.
    float thickness_pixels = t * 0.5 * viewport.y * focal.y / z;
    vec2 free_shift = refraction * thickness_pixels * n.xy;
    float max_shift = max_shift_fraction * viewport.y;
    vec2 shift = free_shift * max_shift * inversesqrt(max_shift * max_shift + dot(free_shift, free_shift));
    // Clamped to the last texel centres of the image in use: beyond them the
    // texture holds stale pixels where an edge texel used to be repeated.
    vec2 shifted = clamp(gl_FragCoord.xy + shift, vec2(0.5), viewport - 0.5);
    vec3 behind = texture(background, shifted / background_texture_size).rgb;
    // The cues dim only what shows through: fluid thick enough to show its
    // own colour (tinted water, colour by attribute) keeps it exactly.
    float contact = 1.0 - smoothstep(0.0, contact_height * particle_radius, z_floor - z);
    float dimming = (1.0 - depth_dimming * (1.0 - exp(-t / (dimming_thickness * particle_radius))))
                  * (1.0 - contact_shadow * contact);
    vec3 refracted = mix(thick_color, dimming * behind, exp(-absorption * t));

    vec3 reflected = reflected_radiance(to_world_point(centre), to_world_direction(reflect(-v, n)));

    // On a silhouette the guessed normal would put highlights on single
    // rim pixels, a dotted line along the edge: only the inside shines.
    vec3 half_vector = normalize(v + light_view);
    float highlight = inside_surface(spans) ? specular_strength * pow(max(dot(n, half_vector), 0.0), shininess) : 0.0;

    vec3 fluid = mix(refracted, reflected, fresnel) + highlight * highlight_radiance;
    // Foam is a diffuse white layer on the surface, lit like one. Without
    // foam there is no noise texture to read: the variant without it has
    // no fetches (a branch on a uniform would: llvmpipe runs both sides).
    if (HAS_FOAM) {
        float foam_amount = min(foam * smoothstep(foam_noise_range.x, foam_noise_range.y, noise_magnitude(p, z)), 1.0);
        vec3 foam_lit = foam_color * (0.6 + 0.4 * max(dot(n, light_view), 0.0));
        fluid = mix(fluid, foam_lit, foam_amount);
    }
    return mix(behind_here, fluid, outline_coverage(p));
}

void main()
{
    float z, z_floor;
    fluid_here(z, z_floor);   // true: the stencil holds where it is
    ivec2 p = ivec2(gl_FragCoord.xy);
    color = vec4(display_color(shade_fluid(p, z, z_floor, texelFetch(background, p, 0).rgb)), 1.0);
}
