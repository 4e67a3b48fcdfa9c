#version 450 core
#ifdef FC_VARIANT
#define WRITES_MASK FC_FLUID_MASK   // shader_variants.h
#else
#define WRITES_MASK 0
#endif
#if WRITES_MASK
#extension GL_ARB_shader_stencil_export : require
#endif
// The scene without fluid, rendered first so the composite pass can sample it
// at refracted positions (van der Laan et al. 2009, §3.5, S in eq. 14): the
// client's background image when it sent one, else the built-in floor and sky.
// The same pass lays down the composite's target where the fluid is not:
// colour and the floor's depth, else the far plane (fluid_mask.frag.glsl then
// writes the fluid's depth), saving the composite a full-screen pass of its own.
// Where the driver lets a shader write the stencil (FC_FLUID_MASK, without
// opaque meshes, which the mask must be tested against), it does the mask's
// work as well: the fluid's depth and stencil 1 on the fluid's pixels, so the
// composite needs no full-screen pass at all (composite_pass.c).

vec3 view_ray(vec2 window);
vec3 to_world_point(vec3 view_point);
vec3 to_world_direction(vec3 view_direction);
vec3 scene_radiance(vec3 origin, vec3 dir);
vec3 display_color(vec3 radiance);
vec3 picture_radiance(vec3 color);
float floor_depth(vec3 ray);
float window_depth(float z);
bool fluid_here(out float z, out float z_floor);

layout(binding = 8) uniform sampler2D client_image;    // linear RGB(A), rows bottom to top as uploaded top-down

layout(location = 5) uniform vec2 viewport;
#ifdef FC_VARIANT
const bool use_client_image = FC_USE_CLIENT_IMAGE != 0;   // shader_variants.h
#else
layout(location = 30) uniform bool use_client_image;
#endif
layout(location = 31) uniform vec2 image_scale;       // viewport uv -> image uv around the centre (cover fit)

layout(location = 0) out vec4 radiance;      // the background texture (RGBA16F), linear HDR
layout(location = 1) out vec4 scene_color;   // the composite's target, display colour

vec3 background_radiance()
{
    if (use_client_image) {
        vec2 uv = 0.5 + (gl_FragCoord.xy / viewport - 0.5) * image_scale;
        // The image's first row is its top, uploaded as the texture's first (bottom) row.
        return picture_radiance(texture(client_image, vec2(uv.x, 1.0 - uv.y)).rgb);
    }
    vec3 dir = normalize(to_world_direction(view_ray(gl_FragCoord.xy)));
    return scene_radiance(to_world_point(vec3(0.0)), dir);
}

void main()
{
    vec3 scene = background_radiance();
    radiance = vec4(scene, 1.0);
    scene_color = vec4(display_color(scene), 1.0);
#if WRITES_MASK
    float z, z_floor;
    bool fluid = fluid_here(z, z_floor);   // as fluid_mask.frag.glsl decides and writes it
    gl_FragDepth = window_depth(fluid ? z : z_floor);
    gl_FragStencilRefARB = fluid ? 1 : 0;
#else
    gl_FragDepth = window_depth(floor_depth(view_ray(gl_FragCoord.xy)));
#endif
}
