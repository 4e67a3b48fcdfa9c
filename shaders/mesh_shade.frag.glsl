#version 450 core
// A mesh lit by the scene's sun and sky (environment.frag.glsl), in the
// shadows of the fluid and of the opaque meshes. Opaque meshes write both
// the scene's radiance (the background texture the fluid refracts) and the
// image's colour; glass writes the colour alone, blended with its opacity.

vec3 view_ray(vec2 window);
vec3 to_world_point(vec3 view_point);
vec3 scene_radiance(vec3 origin, vec3 dir);
vec3 to_world_direction(vec3 view_direction);
vec3 surface_radiance(vec3 point, vec3 normal, vec3 albedo, vec3 view_direction);
vec3 display_color(vec3 radiance);

in vec3 view_position;
in vec3 view_normal;

layout(location = 68) uniform bool has_normals;   // else each triangle is flat
layout(location = 69) uniform vec3 albedo;        // linear RGB
layout(location = 70) uniform float opacity;

layout(location = 0) out vec4 radiance;   // the background texture (opaque meshes only)
layout(location = 1) out vec4 color;      // the image

void main()
{
    vec3 toward_eye = -normalize(view_ray(gl_FragCoord.xy));
    vec3 n = has_normals ? normalize(view_normal) : normalize(cross(dFdx(view_position), dFdy(view_position)));
    // Both sides are lit as the side the camera sees (a tank's inside).
    if (dot(n, toward_eye) < 0.0)
        n = -n;
    vec3 world = to_world_point(view_position);
    vec3 world_n = normalize(to_world_direction(n)), world_eye = normalize(to_world_direction(toward_eye));
    vec3 lit = surface_radiance(world, world_n, albedo, world_eye);
    // Schlick's Fresnel reflection of the scene (a dielectric, F0 = 0.04):
    // grazing faces and glass pick up the sky and the floor.
    float fresnel = 0.04 + 0.96 * pow(1.0 - clamp(dot(n, toward_eye), 0.0, 1.0), 5.0);
    lit = mix(lit, scene_radiance(world, reflect(-world_eye, world_n)), fresnel);
    radiance = vec4(lit, 1.0);
    color = vec4(display_color(lit), opacity);
}
